# SPDX-License-Identifier: BSD-3-Clause
"""The commands end in one line, never a traceback: on SIGINT (status 130) and on any error
of `gencoord info`, `simulate` and `crosscheck` before they build anything."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path

from .refused_cases import PREAMBLE
from .support import BOB, REPO

# writes a marker once the model file runs, then loops until interrupted
_LOOPING = PREAMBLE + BOB + """\
import pathlib
pathlib.Path(__file__).with_suffix(".running").write_text("")
while True:
    pass
"""


def _default_sigint():
    """In the child: SIGINT does its default. A shell starts background jobs with SIGINT
    ignored, and Python then never raises KeyboardInterrupt; a user's terminal does not."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


class InterruptTest(unittest.TestCase):

    def setUp(self):
        scratch = tempfile.TemporaryDirectory(prefix="gencoord-interrupt-")
        self.addCleanup(scratch.cleanup)
        self.root = Path(scratch.name)

    def interrupted(self, *command: str) -> subprocess.CompletedProcess:
        model = self.root / "looping.py"
        model.write_text(_LOOPING)
        process = subprocess.Popen([sys.executable, str(REPO / command[0]), *command[1:],
                                    str(model)], cwd=str(self.root), stdout=subprocess.PIPE,
                                   stderr=subprocess.PIPE, text=True,
                                   env=dict(os.environ, PYTHONHASHSEED="0"),
                                   preexec_fn=_default_sigint)
        deadline = time.monotonic() + 120
        while not model.with_suffix(".running").exists() and time.monotonic() < deadline:
            time.sleep(0.05)
        if not model.with_suffix(".running").exists():
            process.kill()
            process.communicate()
            self.fail("the model file never started running")
        process.send_signal(signal.SIGINT)
        try:
            out, err = process.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            process.kill()
            process.communicate()
            self.fail("the command went on for 60 s after SIGINT")
        return subprocess.CompletedProcess(process.args, process.returncode, out, err)

    def test_generate(self):
        result = self.interrupted("generate")
        self.assertEqual(result.returncode, 130, result.stderr)
        self.assertEqual(result.stderr.strip(), "generate: interrupted")

    def test_gencoord_info(self):
        result = self.interrupted("gencoord", "info")
        self.assertEqual(result.returncode, 130, result.stderr)
        self.assertEqual(result.stderr.strip(), "gencoord: interrupted")


class HangTest(unittest.TestCase):

    def test_a_model_that_ignores_the_time_limit_ends_in_one_line(self):
        """The load limit's signal can be ignored; the watchdog still ends the run."""
        with tempfile.TemporaryDirectory(prefix="gencoord-hang-") as scratch:
            model = Path(scratch) / "stubborn.py"
            model.write_text("import signal\nsignal.signal(signal.SIGALRM, signal.SIG_IGN)\n"
                             + PREAMBLE + BOB + "while True:\n    pass\n")
            result = subprocess.run([sys.executable, str(REPO / "generate"), str(model),
                                     "-o", str(Path(scratch) / "out"), "--load-timeout", "1"],
                                    capture_output=True, text=True, timeout=120,
                                    env=dict(os.environ, PYTHONHASHSEED="0"))
            self.assertEqual(result.returncode, 1, result.stderr)
            self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)
            self.assertIn(f"{model}: error: the model file still ran 1 s", result.stderr)
            self.assertIn("did not stop", result.stderr)
            self.assertFalse((Path(scratch) / "out").exists())


class ToolErrorTest(unittest.TestCase):

    def test_help_says_a_model_file_runs_with_the_users_rights(self):
        for command in (["generate"], ["gencoord"], ["gencoord", "generate"],
                        ["gencoord", "simulate"], ["gencoord", "crosscheck"],
                        ["gencoord", "info"]):
            with self.subTest(command=command):
                result = subprocess.run([sys.executable, str(REPO / command[0]), *command[1:],
                                         "--help"], capture_output=True, text=True, timeout=120,
                                        env=dict(os.environ, PYTHONHASHSEED="0"))
                self.assertEqual(result.returncode, 0, result.stderr)
                text = " ".join(result.stdout.split())
                self.assertRegex(text, r"runs( it)? with your rights")
                self.assertIn("Run only model files you trust", text)

    def test_subcommands_report_a_bad_model_in_one_line(self):
        with tempfile.TemporaryDirectory(prefix="gencoord-tool-") as scratch:
            model = Path(scratch) / "exits.py"
            model.write_text(PREAMBLE + BOB + "raise SystemExit(0)\n")
            for command in ("info", "simulate", "crosscheck", "generate"):
                with self.subTest(command=command):
                    result = subprocess.run(
                        [sys.executable, str(REPO / "gencoord"), command, str(model), "-o",
                         str(Path(scratch) / "out")] if command != "info" else
                        [sys.executable, str(REPO / "gencoord"), command, str(model)],
                        cwd=scratch, capture_output=True, text=True, timeout=120,
                        env=dict(os.environ, PYTHONHASHSEED="0"))
                    self.assertEqual(result.returncode, 1, result.stderr)
                    self.assertNotIn("Traceback", result.stderr)
                    self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)
                    self.assertIn(f"{model}:", result.stderr)
                    self.assertIn("exited", result.stderr)


if __name__ == "__main__":
    unittest.main()
