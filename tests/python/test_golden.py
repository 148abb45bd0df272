# SPDX-License-Identifier: BSD-3-Clause
"""Golden files: regenerating every model reproduces generated/ byte for byte.

The list of models is taken from scripts/regenerate_all.sh itself: a copy of the script runs
in a scratch tree (with the repository's models/ and model list tool) whose ./generate only
records its arguments. Each recorded invocation is then
run with the real ./generate into a temporary folder, under a PYTHONHASHSEED other than 0 so
that the script's own hash-seed pinning is exercised too.

Another SymPy version than the one that wrote generated/ (the SymPy named in each header's
banner) may order terms differently: the byte-for-byte comparisons are then skipped, and the
headers are compared with their arithmetic masked (header_skeleton) instead.
"""

from __future__ import annotations

import difflib
import json
import os
import re
import shutil
import stat
import subprocess
import sys
import tempfile
import unittest
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from gencoord.generate.stages import generate
from gencoord.options import GenerateOptions

from .support import (GENERATED, MODELS, REPO, banner_sympy_version, describe,
                      other_sympy_than_generated, run_generate)

SCRIPT = REPO / "scripts" / "regenerate_all.sh"
HINT = "run scripts/regenerate_all.sh to accept the new output (and review the diff)"
# Files in generated/ that no generator run is expected to produce.
NOT_GENERATED = {"README.md", "CMakeLists.txt", ".gitattributes", ".gitignore"}
MAX_DIFF_LINES = 200

_RECORDER = """#!{python}
import json, os, sys
with open(os.environ["GENCOORD_INVOCATIONS"], "a", encoding="utf-8") as log:
    log.write(json.dumps(sys.argv[1:]) + "\\n")
"""


def script_invocations() -> list[list[str]]:
    """The argument lists scripts/regenerate_all.sh passes to ./generate, in order."""
    with tempfile.TemporaryDirectory(prefix="gencoord-script-") as scratch:
        root = Path(scratch)
        (root / "scripts").mkdir()
        shutil.copy2(SCRIPT, root / "scripts" / SCRIPT.name)
        model_list = Path("python", "gencoord", "tool", "model_list.py")
        (root / model_list.parent).mkdir(parents=True)
        shutil.copy2(REPO / model_list, root / model_list)
        (root / "models").symlink_to(MODELS, target_is_directory=True)
        recorder = root / "generate"
        recorder.write_text(_RECORDER.format(python=sys.executable), encoding="utf-8")
        recorder.chmod(recorder.stat().st_mode | stat.S_IXUSR)
        log = root / "invocations.jsonl"
        env = dict(os.environ, GENCOORD_INVOCATIONS=str(log))
        result = subprocess.run(["bash", str(root / "scripts" / SCRIPT.name)], env=env,
                                capture_output=True, text=True, timeout=60)
        if result.returncode != 0:
            raise AssertionError(f"{SCRIPT} failed with a recording ./generate:"
                                 f"{describe(result)}")
        if not log.exists():
            return []
        return [json.loads(line) for line in log.read_text(encoding="utf-8").splitlines()]


# The arithmetic of a header, which another SymPy version may write differently: the
# statements of temporaries, the right-hand sides of output entries, and operation counts.
_TEMPORARY = re.compile(r"^ +const Scalar tmp\d+ = [^;]*;\n", re.MULTILINE)
_OUTPUT_ENTRY = re.compile(r"^( +(?:result|\(\*\w+\))(?:\(\d+(?:, \d+)?\)|\[\d+\])?) = [^;]*;",
                           re.MULTILINE)
_COUNT_COMMENT = re.compile(r"^ *//.*(?:[Oo]ps:|terms \().*$", re.MULTILINE)


# A split kernel: its parts, and the values they pass on, whose number and cuts follow the
# sizes of SymPy's CSE.
_PART = re.compile(r"^(?P<indent> *)/// Part (?P<k>\d+) of (?P<n>\d+) of (?P<name>\w+)\(\)")
_MASKED_ENTRY = re.compile(r"^ +\S.* = \(expression\);$")
_CARRIED = re.compile(r"std::array<Scalar, \d+> carried;")


def _merged_parts(text: str) -> str:
    """Each split kernel's parts (`/// Part k of n of name()` to the closing brace of part n)
    as one sorted list of the output entries they set: which part sets which entry depends
    on where the cuts fall, so on SymPy's version."""
    lines = text.split("\n")
    out: list[str] = []
    i = 0
    while i < len(lines):
        first = _PART.match(lines[i])
        if not first or first["k"] != "1":
            out.append(lines[i])
            i += 1
            continue
        entries: list[str] = []
        part = 0
        while i < len(lines):
            line = lines[i]
            i += 1
            match = _PART.match(line)
            if match and match["name"] == first["name"]:
                part = int(match["k"])
            if _MASKED_ENTRY.match(line):
                entries.append(line.strip())
            if part == int(first["n"]) and line == first["indent"] + "}":
                break
        out.append(f"{first['indent']}// the parts of {first['name']}() set: "
                   + " ".join(sorted(entries)))
    return _CARRIED.sub("std::array<Scalar, N> carried;", "\n".join(out))


def header_skeleton(text: str) -> str:
    """A generated file with its arithmetic masked: what must not depend on SymPy's version
    (structs, kernel signatures, which outputs are set, the solve, the comments)."""
    text = re.sub(r"(?m)^(//   generator:  gencoord \S+, SymPy )\S+$", r"\1(version)", text)
    text = _TEMPORARY.sub("", text)
    text = _OUTPUT_ENTRY.sub(r"\1 = (expression);", text)
    text = _merged_parts(text)
    return _COUNT_COMMENT.sub(lambda match: re.sub(r"\d+", "N", match.group()), text)


def unified_diff(expected: str, actual: str, name: str) -> str:
    lines = list(difflib.unified_diff(
        expected.splitlines(keepends=True), actual.splitlines(keepends=True),
        fromfile=f"generated/{name} (checked in)", tofile=f"{name} (regenerated)"))
    if len(lines) > MAX_DIFF_LINES:
        lines = lines[:MAX_DIFF_LINES] + [f"... ({len(lines) - MAX_DIFF_LINES} more lines)\n"]
    return "".join(lines)


class GoldenFilesTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.invocations = script_invocations()
        cls.scratch = tempfile.TemporaryDirectory(prefix="gencoord-golden-")
        # run where models/ is the repository's, as the script does, so that the default
        # output (generated/ in the working directory) and the banner's paths are the same
        root = Path(cls.scratch.name)
        (root / "models").symlink_to(MODELS, target_is_directory=True)
        cls.output = root / "generated"

        def run(arguments):
            return run_generate(*arguments, hash_seed="12345", cwd=root)

        with ThreadPoolExecutor(max_workers=max(1, min(4, os.cpu_count() or 1))) as pool:
            cls.results = list(pool.map(run, cls.invocations))

    @classmethod
    def tearDownClass(cls):
        cls.scratch.cleanup()

    def test_script_lists_models(self):
        self.assertGreater(len(self.invocations), 0, f"{SCRIPT} runs ./generate on nothing")
        for arguments in self.invocations:
            models = [a for a in arguments if a.endswith(".py")]
            self.assertEqual(len(models), 1, f"no model file in ./generate {arguments}")
            self.assertTrue((REPO / models[0]).is_file(),
                            f"{SCRIPT} names {models[0]}, which does not exist")
            self.assertNotIn("-o", arguments, "the script must write into generated/")

    def test_every_model_file_is_in_the_script(self):
        listed = {Path(a).name for arguments in self.invocations for a in arguments
                  if a.endswith(".py")}
        missing = sorted(p.name for p in MODELS.glob("*.py"))
        missing = [name for name in missing if name not in listed]
        self.assertEqual(missing, [], f"model files that {SCRIPT} never generates")

    def test_generation_succeeds(self):
        for arguments, result in zip(self.invocations, self.results):
            self.assertEqual(result.returncode, 0, describe(result))
            self.assertEqual(result.stderr, "", f"unexpected output on stderr:"
                                                f"{describe(result)}")

    def test_every_regenerated_header_is_checked_in(self):
        produced = sorted(p.name for p in self.output.iterdir())
        self.assertGreater(len(produced), 0, "nothing was regenerated")
        missing = [name for name in produced if not (GENERATED / name).exists()]
        self.assertEqual(missing, [], "files the script produces that generated/ lacks")

    def test_regenerated_headers_match_generated_byte_for_byte(self):
        names = [p.name for p in sorted(self.output.iterdir()) if (GENERATED / p.name).exists()]
        reason = other_sympy_than_generated(names)
        if reason:
            self.skipTest(reason)
        mismatches = []
        for name in names:
            actual, expected = (self.output / name).read_bytes(), (GENERATED / name).read_bytes()
            if actual != expected:
                mismatches.append(unified_diff(expected.decode("utf-8", "replace"),
                                               actual.decode("utf-8", "replace"), name)
                                  or f"{name}: bytes differ (line endings or encoding)")
        if mismatches:
            self.fail("regenerated headers differ from generated/:\n"
                      + "\n".join(mismatches) + f"\n{HINT}")

    def test_regenerated_headers_match_generated_but_for_arithmetic(self):
        mismatches = []
        for name in sorted(p.name for p in self.output.iterdir()):
            golden = GENERATED / name
            if not golden.exists():
                continue  # test_every_regenerated_header_is_checked_in
            expected = header_skeleton(golden.read_text(encoding="utf-8"))
            actual = header_skeleton((self.output / name).read_text(encoding="utf-8"))
            if actual != expected:
                mismatches.append(unified_diff(expected, actual, name))
        if mismatches:
            self.fail("regenerated headers differ from generated/ in more than their "
                      "arithmetic:\n" + "\n".join(mismatches) + f"\n{HINT}")

    def test_regenerating_gives_the_same_bytes(self):
        arguments = next(a for a in self.invocations if "models/double_pendulum.py" in a)
        with tempfile.TemporaryDirectory(prefix="gencoord-again-") as again:
            # run as setUpClass does (the banner names the working folder's paths)
            root = Path(again)
            (root / "models").symlink_to(MODELS, target_is_directory=True)
            result = run_generate(*arguments, hash_seed="54321", cwd=root)
            self.assertEqual(result.returncode, 0, describe(result))
            name = "double_pendulum.hpp"
            self.assertEqual(sorted(p.name for p in (root / "generated").iterdir()),
                             [name, "double_pendulum.scene.json"])
            first = (self.output / name).read_text(encoding="utf-8")
            second = (root / "generated" / name).read_text(encoding="utf-8")
            self.assertEqual(second, first, "\n" + unified_diff(first, second, name))

    def test_no_stale_files_in_generated(self):
        produced = {p.name for p in self.output.iterdir()}
        stale = sorted(p.name for p in GENERATED.iterdir()
                       if p.name not in produced and p.name not in NOT_GENERATED)
        self.assertEqual(stale, [], "files in generated/ that no entry of "
                         f"{SCRIPT.relative_to(REPO)} produces (stale headers?): delete them "
                         "or add their model to the script")

    def test_no_temporary_files_left(self):
        leftovers = sorted(p.name for p in self.output.iterdir()
                           if not p.name.endswith((".hpp", ".scene.json")))
        self.assertEqual(leftovers, [], "generation left files that are not headers or scenes")


class HeaderSkeletonTest(unittest.TestCase):
    """header_skeleton masks the arithmetic of a kernel and nothing else."""

    KERNEL = ("// Total ops: {ops}\n"
              "  static void f(const QVector<Scalar>& q, Matrix* Mt) {{\n"
              "    const Scalar tmp0 = {tmp};\n"
              "    (*Mt)({row}, 0) = {entry};\n"
              "  }}\n")

    def kernel(self, ops=3, tmp="sin(q(0))", row=0, entry="Scalar(2)*tmp0"):
        return header_skeleton(self.KERNEL.format(ops=ops, tmp=tmp, row=row, entry=entry))

    def test_arithmetic_and_counts_are_masked(self):
        self.assertEqual(self.kernel(), self.kernel(ops=5, tmp="cos(q(1))\n        + q(0)",
                                                    entry="tmp0*tmp0"))

    def test_which_entries_are_set_is_kept(self):
        self.assertNotEqual(self.kernel(), self.kernel(row=1))

    def test_banner_version_is_masked(self):
        banner = "//   generator:  gencoord 0.1.0, SymPy {}\n"
        self.assertEqual(header_skeleton(banner.format("1.11.1")),
                         header_skeleton(banner.format("1.14.0")))
        self.assertEqual(banner_sympy_version(banner.format("1.11.1")), "1.11.1")


class DeterminismTest(unittest.TestCase):
    """Generating in one process twice (with another model in between) gives the same text."""

    def test_same_model_twice_in_one_process(self):
        path = str(MODELS / "double_pendulum.py")
        first = generate(path).header
        generate(str(MODELS / "n_link_chain.py"), {"n": "2"})  # state must not leak
        second = generate(path).header
        self.assertEqual(first, second,
                         "\n" + unified_diff(first, second, "double_pendulum.hpp"))

    def test_options_do_not_leak_between_runs(self):
        path = str(MODELS / "n_link_chain.py")
        with_option = generate(path, {"n": "2"})
        without = generate(path)
        self.assertEqual(with_option.name, "n_link_chain_2")
        self.assertEqual(without.name, "n_link_chain_3", "the default n = 3 must apply again")
        again = generate(path, {"n": "2"})
        self.assertEqual(with_option.header, again.header)

    def test_in_process_generation_matches_golden(self):
        name = "spring_pendulum.hpp"
        reason = other_sympy_than_generated([name])
        if reason:
            self.skipTest(reason)
        # the checked-in headers are generated with --maximal (scripts/regenerate_all.sh)
        header = generate(str(MODELS / "spring_pendulum.py"), {},
                          GenerateOptions(maximal=True)).header
        expected = (GENERATED / name).read_text(encoding="utf-8")
        self.assertEqual(header, expected, "\n" + unified_diff(expected, header, name)
                         + f"\n{HINT}")


if __name__ == "__main__":
    unittest.main()
