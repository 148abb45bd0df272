# SPDX-License-Identifier: BSD-3-Clause
"""The README's Python session (the first ```python block under "## From Python") runs as
written against the built double_pendulum module: it simulates and writes its plot."""

import contextlib
import os
import re
import tempfile
import unittest

import matplotlib

matplotlib.use("Agg")  # a test has no display

import numpy as np  # noqa: E402

REPOSITORY = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def readme_session() -> str:
    with open(os.path.join(REPOSITORY, "README.md"), encoding="utf-8") as handle:
        readme = handle.read()
    section = readme[readme.index("## From Python"):]
    section = section[:section.index("\n## ", 1)]
    return re.search(r"```python\n(.*?)```", section, re.DOTALL).group(1)


class ReadmeSessionTest(unittest.TestCase):
    def test_the_session_simulates_and_plots(self):
        session = readme_session()
        self.assertLessEqual(len(session.splitlines()), 3, "the README promises three lines")
        names = {}
        with tempfile.TemporaryDirectory() as folder, _chdir(folder):
            exec(compile(session, "README.md", "exec"), names)  # noqa: S102
            with open("double_pendulum.png", "rb") as handle:
                self.assertEqual(handle.read(8), b"\x89PNG\r\n\x1a\n")
        t, q, energy = names["t"], names["q"], names["energy"]
        self.assertEqual(q.shape, (10001, 2))
        self.assertAlmostEqual(t[-1], 10.0, places=12)
        # RK4 at dt = 1e-3 keeps the double pendulum's energy to far better than 1e-6
        self.assertLess(np.abs(energy - energy[0]).max(), 1e-6 * abs(energy[0]))
        self.assertGreater(np.ptp(q[:, 0]), 0.1, "the pendulum should swing")


@contextlib.contextmanager
def _chdir(folder: str):
    previous = os.getcwd()
    os.chdir(folder)
    try:
        yield
    finally:
        os.chdir(previous)


if __name__ == "__main__":
    unittest.main()
