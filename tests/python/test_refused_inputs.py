# SPDX-License-Identifier: BSD-3-Clause
"""Inputs the generator refuses: each ends in one `file:line: error: ...` line naming what is
wrong, a non-zero exit, no traceback and an output folder left as it was.

The cases (refused_cases.py) run in this process, through gencoord.generate.cli.main, so that the
table stays fast; test_interrupts.py runs the commands themselves.
"""

from __future__ import annotations

import contextlib
import io
import tempfile
import textwrap
import unittest
from pathlib import Path
from types import SimpleNamespace
from unittest import mock

from gencoord.generate import cli

from gencoord.generate import limits

from gencoord.generate import stages as pipeline

from . import refused_cases
from .support import MARK, MODELS, marked_line, snapshot, snapshot_difference


def run_cli(*arguments: str) -> tuple[int, str, str]:
    """(exit status, stdout, stderr) of generate with these arguments, in this process."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = cli.main([str(a) for a in arguments])
    return status, out.getvalue(), err.getvalue()


class RefusedInputTest(unittest.TestCase):

    def setUp(self):
        scratch = tempfile.TemporaryDirectory(prefix="gencoord-refused-")
        self.addCleanup(scratch.cleanup)
        self.root = Path(scratch.name)
        self.output = self.root / "out"
        self.output.mkdir()
        (self.output / "kept.hpp").write_text("// an older header: must survive\n")

    def write(self, stem: str, source: str, encoding: str = "utf-8") -> Path:
        path = self.root / f"{stem}.py"
        path.write_bytes(textwrap.dedent(source).encode(encoding))
        return path

    def expect_refused(self, path: Path, words: list[str], line: int | None, *extra: str):
        before = snapshot(self.output)
        status, out, err = run_cli(path, "-o", self.output, *extra)
        details = f"\n  status {status}\n  stdout:\n{out}\n  stderr:\n{err}"
        self.assertNotEqual(status, 0, f"accepted:{details}")
        self.assertNotIn("Traceback", err, details)
        self.assertEqual(len(err.strip().splitlines()), 1, f"not one line:{details}")
        where = f"{path}:{line}: error: " if line is not None else f"{path}"
        self.assertIn(where, err, details)
        for word in words:
            self.assertIn(word, err, f"the message must say {word!r}:{details}")
        self.assertEqual(snapshot_difference(before, snapshot(self.output)), "", details)
        return err

    def check_table(self, table: dict):
        for stem, (source, words) in table.items():
            with self.subTest(case=stem):
                source = textwrap.dedent(source)
                self.expect_refused(self.write(stem, source), words, marked_line(source))

    def test_model_files_that_exit(self):
        self.check_table(refused_cases.EXITS)

    def test_reserved_names(self):
        self.check_table(refused_cases.NAMES)

    def test_numbers_that_are_not_finite(self):
        self.check_table(refused_cases.NON_FINITE)

    def test_expressions_that_are_not_smooth_or_not_closed_forms(self):
        self.check_table(refused_cases.NOT_SMOOTH)

    def test_bodies_and_torques(self):
        self.check_table(refused_cases.BODIES)

    def test_declarations_and_descriptions(self):
        self.check_table(refused_cases.DECLARATIONS)

    def test_float_option_that_is_not_finite(self):
        path = self.write("scaled", refused_cases.PREAMBLE + (
            'scale = model.option("scale", 1.0, "a length (m)")  ' + MARK + "\n"
            + refused_cases.BOB))
        self.expect_refused(path, ["option 'scale'", "nan", "finite"], 5, "--set", "scale=nan")

    def test_file_stems_that_are_not_identifiers(self):
        source = refused_cases.PREAMBLE + refused_cases.BOB
        for stem, words in {"1pendulum": ["'1pendulum'", "--name pendulum_1"],
                            "__": ["'__'", "--name model"],
                            "errno": ["'errno'", "macro", "--name errno_model"],
                            "class": ["'class'", "keyword", "--name class_model"],
                            "q_vector": ["QVector", "--name q_vector_model"]}.items():
            with self.subTest(stem=stem):
                self.expect_refused(self.write(stem, source), ["from the file name", *words],
                                    None)
        self.expect_refused(self.write("pendulum_like", source), ["given with --name", "9x"],
                            None, "--name", "9x")

    def test_name_option_names_the_header_and_the_regenerate_line(self):
        path = self.write("1pendulum", refused_cases.PREAMBLE + refused_cases.BOB)
        status, _, err = run_cli(path, "-o", self.output, "--quiet", "--name", "pendulum_1")
        self.assertEqual(status, 0, err)
        header = (self.output / "pendulum_1.hpp").read_text()
        self.assertTrue("struct Pendulum1 {" in header, "the type is named after --name")
        # the banner's regenerate command, which line_wrap may break after --name
        self.assertRegex(header[:1000], r"--name\s+(//\s+)?pendulum_1")

    def test_endless_loop_in_the_model_file(self):
        path = self.write("looping", refused_cases.PREAMBLE + refused_cases.BOB
                          + "while True:  " + MARK + "\n    pass\n")
        self.expect_refused(path, ["still ran after 1 s", "--load-timeout"], None,
                            "--load-timeout", "1")

    def test_option_too_large_for_the_load_timeout(self):
        self.expect_refused(MODELS / "n_link_chain.py", ["still ran after 2 s"], None,
                            "--set", "n=100000", "--load-timeout", "2")

    def test_warning_before_a_long_generation(self):
        path = self.write("pendulum_like", refused_cases.PREAMBLE + refused_cases.BOB)
        with mock.patch.object(pipeline, "size_warning", return_value="expected to be long"):
            status, _, err = run_cli(path, "-o", self.output, "--quiet")
        self.assertEqual(status, 0, err)
        self.assertEqual(err.strip(), f"{path}: warning: expected to be long")
        text = limits.size_warning(SimpleNamespace(nq=100000, particles=[]))
        self.assertIn("100000 coordinates", text)
        self.assertIn("days", text)
        self.assertIsNone(limits.size_warning(SimpleNamespace(nq=50, particles=[])))
        # a tree is derived by its recursions: 400 links take about a minute, no warning
        self.assertIsNone(limits.size_warning(SimpleNamespace(nq=400, particles=[]), tree=True))
        self.assertIn("nq^2", limits.size_warning(SimpleNamespace(nq=400, particles=[])))
        self.assertIn("minutes", limits.size_warning(SimpleNamespace(nq=2000, particles=[]),
                                                     tree=True))

    def test_latin1_file(self):
        path = self.write("latin1", refused_cases.PREAMBLE + 'model.description = "caf\u00e9"\n'
                          + refused_cases.BOB, encoding="latin-1")
        self.expect_refused(path, ["UTF-8", "coding"], None)

    def test_latin1_file_that_declares_its_encoding_is_read(self):
        path = self.write("declared", "# -*- coding: latin-1 -*-\n" + refused_cases.PREAMBLE
                          + 'model.description = "caf\u00e9"\n' + refused_cases.BOB,
                          encoding="latin-1")
        status, out, err = run_cli(path, "-o", self.output, "--quiet")
        self.assertEqual(status, 0, err)

    def test_unexpected_exception_is_one_line_and_verbose_shows_the_traceback(self):
        path = self.write("pendulum_like", refused_cases.PREAMBLE + refused_cases.BOB)
        with mock.patch("gencoord.generate.stages.generate",
                        side_effect=RuntimeError("boom\nsecond")):
            err = self.expect_refused(path, ["internal error", "RuntimeError", "boom second",
                                             "--verbose"], None)
            status, _, verbose = run_cli(path, "-o", self.output, "--verbose")
        self.assertEqual(status, 1)
        self.assertIn("Traceback", verbose)
        self.assertIn(err.strip(), verbose)

    def test_keyboard_interrupt_is_one_line_and_status_130(self):
        path = self.write("pendulum_like", refused_cases.PREAMBLE + refused_cases.BOB)
        with mock.patch("gencoord.generate.stages.generate", side_effect=KeyboardInterrupt):
            status, _, err = run_cli(path, "-o", self.output)
        self.assertEqual(status, 130)
        self.assertEqual(err.strip(), "generate: interrupted")

    def test_unwritable_output_folder(self):
        path = self.write("pendulum_like", refused_cases.PREAMBLE + refused_cases.BOB)
        blocker = self.root / "a_file"
        blocker.write_text("not a folder\n")
        status, _, err = run_cli(path, "-o", blocker / "sub", "--quiet")
        self.assertEqual(status, 1, err)
        self.assertNotIn("Traceback", err)
        self.assertIn("error:", err)


if __name__ == "__main__":
    unittest.main()
