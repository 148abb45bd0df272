# SPDX-License-Identifier: BSD-3-Clause
"""Which interpreter `gencoord python` builds for, and the guard written beside the module
that tells any other interpreter which one to use."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys


def _has_numpy(python: str) -> bool:
    try:
        return subprocess.run([python, "-c", "import numpy"], capture_output=True,
                              timeout=60, check=False).returncode == 0
    except (OSError, subprocess.TimeoutExpired):
        return False


def interpreter_version(python: str) -> str:
    """The version of an interpreter, e.g. 3.11.2 ("unknown" if it does not run)."""
    result = subprocess.run([python, "-c", "import platform; print(platform.python_version())"],
                            capture_output=True, text=True, timeout=60, check=False)
    return result.stdout.strip() or "unknown"


def default_python() -> str:
    """The first interpreter that can import NumPy, which every model module needs: the one
    running gencoord, the `python3` on PATH, Debian's /usr/bin/python3; else the one running
    gencoord (its module then says on import that NumPy is missing)."""
    candidates = [sys.executable, shutil.which("python3"), "/usr/bin/python3"]
    seen = set()
    for python in candidates:
        if not python or not os.path.isfile(python) or os.path.realpath(python) in seen:
            continue
        seen.add(os.path.realpath(python))
        if _has_numpy(python):
            return python
    return sys.executable


_GUARD = '''\
"""Written by gencoord python beside {module_file}: Python loads this file only when it cannot
load that module, which was built for {python} (Python {version})."""
import sys

raise ImportError(
    "{name}: the module in this folder was built by gencoord python for {python} "
    "(Python {version}), and this interpreter (" + sys.executable + ", Python "
    + sys.version.split()[0] + ") cannot load it: run that one, or build for this one "
    "with gencoord python MODEL --python " + sys.executable)
'''


def write_import_guard(module_path: str, name: str, python: str, version: str) -> str:
    """Writes <name>.py beside the module: an extension module comes first in Python's search
    of a folder, so this file is imported only by an interpreter that cannot load the module
    (another Python version), and it says which interpreter to use. Returns its path."""
    guard = os.path.join(os.path.dirname(module_path), name + ".py")
    partial = guard + ".partial"
    with open(partial, "w", encoding="utf-8") as handle:
        handle.write(_GUARD.format(module_file=os.path.basename(module_path), name=name,
                                   python=python, version=version))
    os.replace(partial, guard)
    return guard
