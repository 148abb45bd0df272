# SPDX-License-Identifier: BSD-3-Clause
"""The command line: ./generate models/<name>.py [-o DIR] [--set n=5] [-v]."""

from __future__ import annotations

import ast
import re
import shlex
import shutil
import subprocess
import tempfile
import unittest
from pathlib import Path

from .support import GENERATED, MODELS, describe, run_generate, snapshot, snapshot_difference

STAGES = ("load", "check", "derive", "optimize (CSE)", "emit")


class CommandLineTest(unittest.TestCase):

    def setUp(self):
        self.scratch = tempfile.TemporaryDirectory(prefix="gencoord-cli-")
        self.output = Path(self.scratch.name)

    def tearDown(self):
        self.scratch.cleanup()

    def generate(self, *arguments: str):
        result = run_generate(*arguments, "-o", self.output)
        self.assertEqual(result.returncode, 0, describe(result))
        return result

    def test_pendulum_header(self):
        result = self.generate("models/pendulum.py")
        self.assertEqual(sorted(p.name for p in self.output.iterdir()),
                         ["pendulum.hpp", "pendulum.scene.json"])
        header = (self.output / "pendulum.hpp").read_text(encoding="utf-8")
        banner = header[:header.index("#pragma once")]
        self.assertRegex(banner.splitlines()[0], r"(?i)do not (modify|edit)",
                         f"no do-not-edit banner on the first line:\n{banner}")
        self.assertIn("models/pendulum.py", banner, banner)
        self.assertIn("gencoord/cxx/templates/model.hpp.j2", banner, banner)
        self.assertRegex(banner, r"Total ops: \d+", banner)
        docstring = ast.get_docstring(ast.parse((MODELS / "pendulum.py").read_text()))
        for line in filter(None, (text.strip() for text in docstring.splitlines())):
            self.assertIn(line, header, "the model's docstring is not in the header")
        self.assertRegex(header, r"\bstruct Pendulum\b")
        self.assertRegex(header, r"\bnq = 1;")
        self.assertIn("wrote", result.stdout, describe(result))
        self.assertIn("pendulum.hpp", result.stdout, describe(result))

    def test_unchanged_header_is_not_rewritten(self):
        self.generate("models/pendulum.py", "--quiet")
        path = self.output / "pendulum.hpp"
        before = path.stat().st_mtime_ns, path.read_bytes()
        result = self.generate("models/pendulum.py")
        self.assertIn("unchanged", result.stdout, describe(result))
        self.assertEqual((path.stat().st_mtime_ns, path.read_bytes()), before,
                         "an identical header was rewritten (it would trigger rebuilds)")

    def test_quiet_prints_nothing(self):
        result = self.generate("models/pendulum.py", "--quiet")
        self.assertEqual((result.stdout, result.stderr), ("", ""), describe(result))

    def test_set_option_names_header_and_type(self):
        self.generate("models/n_link_chain.py", "--set", "n=5", "--quiet")
        self.assertEqual(sorted(p.name for p in self.output.iterdir()),
                         ["n_link_chain_5.hpp", "n_link_chain_5.scene.json"])
        header = (self.output / "n_link_chain_5.hpp").read_text(encoding="utf-8")
        self.assertRegex(header, r"\bstruct NLinkChain5\b")
        self.assertRegex(header, r"\bnq = 5;")
        self.assertIn("theta5", header)
        self.assertNotIn("theta6", header)

    def test_verbose_prints_a_timed_line_per_stage(self):
        result = self.generate("models/n_link_chain.py", "--set", "n=10", "-v")
        for stage in STAGES:
            self.assertRegex(result.stdout, rf"(?m)^\s*{re.escape(stage)}\s+\d+\.\d+ s$",
                             f"no timing line for stage '{stage}':{describe(result)}")
        self.assertTrue((self.output / "n_link_chain_10.hpp").is_file())


def regenerate_command(header: str) -> list[str]:
    """The arguments of the banner's `regenerate: gencoord generate ...` line."""
    match = re.search(r"^//   regenerate: gencoord generate (.*)$", header, re.M)
    if match is None:
        raise AssertionError(f"no 'regenerate: gencoord generate' line in:\n{header[:600]}")
    return shlex.split(match.group(1))


class OutputNextToTheUserTest(unittest.TestCase):
    """Without -o the header goes to generated/ in the working directory, and the banner's
    regenerate command works from there."""

    def setUp(self):
        self.scratch = tempfile.TemporaryDirectory(prefix="gencoord-user-")
        root = Path(self.scratch.name)
        self.work = root / "work"
        self.work.mkdir()
        (root / "elsewhere").mkdir()
        self.model = root / "elsewhere" / "crane.py"
        shutil.copy2(MODELS / "pendulum.py", self.model)

    def tearDown(self):
        self.scratch.cleanup()

    def test_default_output_is_generated_in_the_working_directory(self):
        checkout_before = snapshot(GENERATED)
        result = run_generate("../elsewhere/crane.py", "--quiet", cwd=self.work)
        self.assertEqual(result.returncode, 0, describe(result))
        self.assertEqual(sorted(p.name for p in (self.work / "generated").iterdir()),
                         ["crane.hpp", "crane.scene.json"])
        self.assertEqual(snapshot_difference(checkout_before, snapshot(GENERATED)), "",
                         "generation outside the checkout wrote into its generated/")
        header = (self.work / "generated" / "crane.hpp").read_text(encoding="utf-8")
        self.assertIn("//   model:      ../elsewhere/crane.py\n", header)
        self.assertEqual(regenerate_command(header), ["../elsewhere/crane.py"])

    def test_regenerate_line_reproduces_the_header_from_the_working_directory(self):
        arguments = [str(self.model), "-o", "out dir", "--max-function-statements", "4"]
        result = run_generate(*arguments, "--quiet", cwd=self.work)
        self.assertEqual(result.returncode, 0, describe(result))
        header = (self.work / "out dir" / "crane.hpp").read_text(encoding="utf-8")
        command = regenerate_command(header)
        self.assertEqual(command, ["../elsewhere/crane.py", "--max-function-statements", "4",
                                   "-o", "out dir"])
        shutil.rmtree(self.work / "out dir")
        result = run_generate(*command, "--quiet", cwd=self.work)
        self.assertEqual(result.returncode, 0, describe(result))
        self.assertEqual((self.work / "out dir" / "crane.hpp").read_text(encoding="utf-8"),
                         header, "the banner's command did not reproduce the header")

    def test_paths_with_line_breaks_stay_inside_the_banner_comment(self):
        odd = self.model.parent.parent / "line\nbreak\\"
        odd.mkdir()
        shutil.copy2(self.model, odd / "crane.py")
        result = run_generate(str(odd / "crane.py"), "-o", "out\ndir", "--quiet", cwd=self.work)
        self.assertEqual(result.returncode, 0, describe(result))
        header = (self.work / "out\ndir" / "crane.hpp").read_text(encoding="utf-8")
        banner = header.split("\n//\n", 1)[0].splitlines()
        self.assertEqual(len(banner), 5, banner)
        for line in banner:
            self.assertTrue(line.startswith("// ") and not line.endswith("\\"), line)
        command = re.search(r"^//   regenerate: gencoord generate (.*)$", header, re.M).group(1)
        words = subprocess.run(["bash", "-c", "printf '%s\\0' " + command], check=True,
                               capture_output=True, text=True).stdout.split("\0")[:-1]
        self.assertEqual(words, ["../line\nbreak\\/crane.py", "-o", "out\ndir"])

    def test_options_appear_in_the_regenerate_line(self):
        result = run_generate(str(MODELS / "n_link_chain.py"), "--set", "n=2", "--quiet",
                              cwd=self.work)
        self.assertEqual(result.returncode, 0, describe(result))
        header = (self.work / "generated" / "n_link_chain_2.hpp").read_text(encoding="utf-8")
        model, *options = regenerate_command(header)
        self.assertEqual(options, ["--set", "n=2"])
        self.assertFalse(Path(model).is_absolute(), "the model path must be relative")
        self.assertEqual((self.work / model).resolve(), (MODELS / "n_link_chain.py").resolve())

    def test_help_states_the_default_output(self):
        result = run_generate("--help")
        self.assertEqual(result.returncode, 0, describe(result))
        self.assertRegex(" ".join(result.stdout.split()),
                         r"default: generated/ in the current directory")


if __name__ == "__main__":
    unittest.main()
