# SPDX-License-Identifier: BSD-3-Clause
"""gencoord python's choice of interpreter and the guard it writes beside a module."""

from __future__ import annotations

import subprocess
import sys
import tempfile
import unittest
from pathlib import Path
from unittest import mock

REPOSITORY = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPOSITORY / "python"))
from gencoord.tool import python_target  # noqa: E402


class ImportGuardTest(unittest.TestCase):

    def test_an_interpreter_that_cannot_load_the_module_is_told_which_can(self):
        with tempfile.TemporaryDirectory(prefix="gencoord-guard-") as folder:
            # a module for another Python: this interpreter's suffix does not match it
            module = Path(folder) / "crane.cpython-10-made-up.so"
            module.write_bytes(b"")
            guard = python_target.write_import_guard(str(module), "crane", "/opt/py/python3",
                                                     "3.99.1")
            self.assertEqual(Path(guard), Path(folder) / "crane.py")
            result = subprocess.run([sys.executable, "-c", "import crane"], cwd=folder,
                                    capture_output=True, text=True, check=False)
        self.assertNotEqual(result.returncode, 0)
        last = result.stderr.strip().splitlines()[-1]
        self.assertTrue(last.startswith("ImportError: crane: the module in this folder was "
                                        "built by gencoord python for /opt/py/python3 "
                                        "(Python 3.99.1)"), last)
        self.assertIn(f"--python {sys.executable}", last)


class DefaultPythonTest(unittest.TestCase):

    def test_the_first_interpreter_with_numpy(self):
        with mock.patch.object(python_target, "_has_numpy", side_effect=lambda p: p == "/b"), \
                mock.patch.object(python_target.shutil, "which", return_value="/b"), \
                mock.patch.object(python_target.os.path, "isfile", return_value=True), \
                mock.patch.object(python_target.sys, "executable", "/a"):
            self.assertEqual(python_target.default_python(), "/b")

    def test_the_running_one_when_none_has_numpy(self):
        with mock.patch.object(python_target, "_has_numpy", return_value=False), \
                mock.patch.object(python_target.sys, "executable", "/a"):
            self.assertEqual(python_target.default_python(), "/a")

    def test_the_running_one_first_when_it_has_numpy(self):
        with mock.patch.object(python_target, "_has_numpy", return_value=True), \
                mock.patch.object(python_target.os.path, "isfile", return_value=True), \
                mock.patch.object(python_target.sys, "executable", "/a"):
            self.assertEqual(python_target.default_python(), "/a")


if __name__ == "__main__":
    unittest.main()
