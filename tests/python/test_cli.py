"""The command line: ./generate models/<name>.py [-o DIR] [--set n=5] [-v]."""

from __future__ import annotations

import ast
import re
import tempfile
import unittest
from pathlib import Path

from .support import MODELS, describe, run_generate

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
        self.assertEqual(sorted(p.name for p in self.output.iterdir()), ["pendulum.hpp"])
        header = (self.output / "pendulum.hpp").read_text(encoding="utf-8")
        banner = header[:header.index("#pragma once")]
        self.assertRegex(banner.splitlines()[0], r"(?i)do not (modify|edit)",
                         f"no do-not-edit banner on the first line:\n{banner}")
        self.assertIn("models/pendulum.py", banner, banner)
        self.assertIn("templates/model.hpp.j2", banner, banner)
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
        self.assertEqual(sorted(p.name for p in self.output.iterdir()), ["n_link_chain_5.hpp"])
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


if __name__ == "__main__":
    unittest.main()
