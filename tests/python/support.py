# SPDX-License-Identifier: BSD-3-Clause
"""Shared helpers of the generator tests: paths, running ./generate, directory snapshots,
numerical comparison in extended precision (mpmath; numpy is not available)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import mpmath
import sympy as sp

REPO = Path(__file__).resolve().parents[2]
GENERATE = REPO / "generate"
MODELS = REPO / "models"
GENERATED = REPO / "generated"

# Working precision of every numerical comparison; tolerances are far above its round-off.
DIGITS = 30


_BANNER_SYMPY = re.compile(r"^//   generator:  gencoord \S+, SymPy (\S+)$", re.MULTILINE)


def banner_sympy_version(text: str) -> str | None:
    """The SymPy version a generated file's banner names (None without a banner)."""
    match = _BANNER_SYMPY.search(text)
    return match.group(1) if match else None


def other_sympy_than_generated(names) -> str | None:
    """Why the files `names` of generated/ cannot be compared byte for byte with what this
    SymPy writes (another version may order terms differently), or None when they can."""
    versions = {banner_sympy_version((GENERATED / name).read_text(encoding="utf-8"))
                for name in names} - {None}  # a scene (JSON) has no banner
    others = sorted(str(v) for v in versions if v != sp.__version__)
    if not others:
        return None
    return (f"generated/ was written with SymPy {', '.join(others)}, this is SymPy "
            f"{sp.__version__}: byte-for-byte comparison skipped (term order may differ)")


def run_generate(*args: str, hash_seed: str | None = None, timeout: float = 300,
                 cwd: Path = REPO) -> subprocess.CompletedProcess:
    """Runs ./generate with this interpreter; `hash_seed` overrides PYTHONHASHSEED."""
    env = dict(os.environ)
    if hash_seed is not None:
        env["PYTHONHASHSEED"] = hash_seed
    return subprocess.run([sys.executable, str(GENERATE), *map(str, args)], cwd=str(cwd),
                          env=env, capture_output=True, text=True, timeout=timeout)


def describe(result: subprocess.CompletedProcess) -> str:
    """A process's exit status and output, for failure messages."""
    return (f"\n  command: {' '.join(map(str, result.args))}\n  exit status: "
            f"{result.returncode}\n  stdout:\n{result.stdout}\n  stderr:\n{result.stderr}")


def snapshot(directory: Path) -> dict[str, tuple[bytes, int, int]]:
    """Every entry below `directory` (hidden ones too): relative path -> (bytes, mtime_ns,
    mode); directories map to (b'<dir>', mtime_ns, mode)."""
    state = {}
    for root, dirs, files in os.walk(directory):
        for name in dirs:
            path = Path(root, name)
            info = path.stat()
            state[str(path.relative_to(directory)) + "/"] = (b"<dir>", info.st_mtime_ns,
                                                             info.st_mode)
        for name in files:
            path = Path(root, name)
            info = path.stat()
            state[str(path.relative_to(directory))] = (path.read_bytes(), info.st_mtime_ns,
                                                       info.st_mode)
    return state


def snapshot_difference(before: dict, after: dict) -> str:
    """A readable account of what changed between two snapshots ('' when nothing did)."""
    lines = []
    for name in sorted(set(before) | set(after)):
        if name not in after:
            lines.append(f"  removed: {name}")
        elif name not in before:
            lines.append(f"  created: {name}")
        elif before[name] != after[name]:
            old, new = before[name], after[name]
            what = [label for label, a, b in zip(("contents", "mtime", "mode"), old, new)
                    if a != b]
            lines.append(f"  changed ({', '.join(what)}): {name}")
    return "\n".join(lines)


def lambdify_flat(args, matrix):
    """A function of `args` returning the entries of `matrix` (row major) as mpmath numbers."""
    return sp.lambdify(args, list(matrix), modules="mpmath")


def max_abs(values) -> mpmath.mpf:
    return max((abs(mpmath.mpmathify(x)) for x in values), default=mpmath.mpf(0))


def relative_error(actual, expected) -> mpmath.mpf:
    """max |actual - expected| / max |expected| over all entries (entries in any order
    that zip() pairs up; both sequences must have the same length)."""
    actual, expected = list(actual), list(expected)
    if len(actual) != len(expected):
        raise AssertionError(f"lengths differ: {len(actual)} != {len(expected)}")
    scale = max_abs(expected)
    difference = max_abs(a - e for a, e in zip(actual, expected))
    if scale == 0:
        return difference
    return difference / scale


def format_numbers(values, digits: int = 17) -> str:
    return "[" + ", ".join(mpmath.nstr(mpmath.mpf(x), digits) for x in values) + "]"


# Bad-model sources mark the line their error must name with MARK; BOB is a pendulum bob.
MARK = "# <- error"
BOB = 'bob = model.particle("bob", mass=1, position=[sin(theta), -cos(theta)])\n'


def marked_line(source: str) -> int | None:
    """The number of the line of `source` that holds MARK, or None."""
    for number, line in enumerate(source.splitlines(), start=1):
        if MARK in line:
            return number
    return None
