# SPDX-License-Identifier: BSD-3-Clause
"""The viewer page in a real browser (headless Chromium, WebGL on its CPU renderer): no
console errors; after a seek the bob is drawn where the trajectory puts it, read both from the
page and from the pixels of a screenshot; playing advances time; the energy plot spans the
drift the CSV holds. Screenshots are kept in $GENCOORD_VIEWER_ARTIFACTS (CTest: the build
tree), else in a temporary folder.

GENCOORD_SKIP_BROWSER=1 skips these tests where no browser may run; everywhere else a
missing Chromium is a failure that says how to install it."""

from __future__ import annotations

import os
import tempfile
import time
import unittest

from gencoord.tool.trajectory_svg import energy_error, read_trajectory
from gencoord.viewer import page
from gencoord.viewer.headless import Browser, find_chromium
from gencoord.viewer.in_browser import open_viewer
from gencoord.viewer.png import read_png

from .trajectory import double_pendulum_csv, double_pendulum_scene

WIDTH, HEIGHT = 1000, 700
TOLERANCE_PX = 2.0
BOB = "bob2"


def colour_centroid(png: bytes, colour, region, tolerance: int = 12):
    """The mean pixel position (x, y) of the pixels within `tolerance` of `colour` in
    `region` (left, top, right, bottom), with their count; pixel centres at +0.5."""
    width, height, channels, rows = read_png(png)
    left, top, right, bottom = (int(v) for v in region)
    sum_x = sum_y = count = 0
    for y in range(max(0, top), min(height, bottom)):
        row = rows[y]
        for x in range(max(0, left), min(width, right)):
            pixel = row[x * channels:x * channels + 3]
            if all(abs(pixel[c] - colour[c]) <= tolerance for c in range(3)):
                sum_x, sum_y, count = sum_x + x + 0.5, sum_y + y + 0.5, count + 1
    return (sum_x / count, sum_y / count, count) if count else (None, None, 0)


@unittest.skipIf(os.environ.get("GENCOORD_SKIP_BROWSER") == "1", "GENCOORD_SKIP_BROWSER=1")
class BrowserTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        if not find_chromium():
            raise AssertionError("no Chromium: run scripts/setup.sh --browser (Debian's "
                                 "chromium package), or set GENCOORD_CHROMIUM")
        cls.artifacts = os.environ.get("GENCOORD_VIEWER_ARTIFACTS") or tempfile.mkdtemp(
            prefix="gencoord-viewer-")
        os.makedirs(cls.artifacts, exist_ok=True)
        cls.csv = double_pendulum_csv()
        cls.trajectory = read_trajectory(cls.csv)
        cls.html = os.path.join(cls.artifacts, "double_pendulum.html")
        page.write_page(cls.csv, double_pendulum_scene(), cls.html, "double_pendulum")
        cls.browser = Browser(width=WIDTH, height=HEIGHT)
        cls.browser.__enter__()
        cls.page = open_viewer(cls.browser, cls.html)
        cls.page.evaluate("gencoordViewer.setTrails(false)")

    @classmethod
    def tearDownClass(cls):
        cls.browser.__exit__(None, None, None)

    def viewer(self, call: str):
        return self.page.evaluate("gencoordViewer." + call)

    def keep(self, png: bytes, name: str) -> None:
        with open(os.path.join(self.artifacts, name), "wb") as handle:
            handle.write(png)

    def test_1_no_console_errors(self):
        self.viewer("seek(3.0)")
        self.assertEqual(self.page.console_errors, [])

    def test_2_a_seek_draws_the_bob_where_the_trajectory_puts_it(self):
        t, xs, ys = self.trajectory.t, self.trajectory.path(BOB, "x"), self.trajectory.path(
            BOB, "y")
        colour = self.viewer(f"particleColour('{BOB}')")
        view_bottom = self.page.evaluate("document.getElementById('view')"
                                         ".getBoundingClientRect().bottom")
        checked = 0
        for row in range(250, len(t), 1650):
            if (xs[row] ** 2 + ys[row] ** 2) < 0.25:
                continue  # near the pivot's marker, which would cover part of the bob
            with self.subTest(t=t[row]):
                self.assertEqual(self.viewer(f"seek({t[row]!r})"), t[row])
                expected = self.viewer(f"project({xs[row]!r}, {ys[row]!r})")
                drawn = self.viewer(f"particleOnScreen('{BOB}')")
                self.assertLessEqual(abs(drawn[0] - expected[0]), TOLERANCE_PX)
                self.assertLessEqual(abs(drawn[1] - expected[1]), TOLERANCE_PX)
                png = self.page.screenshot()
                self.keep(png, f"seek_{t[row]:.3f}.png")
                x, y, count = colour_centroid(png, colour, (0, 0, WIDTH, view_bottom))
                self.assertGreater(count, 50, f"the bob's colour {colour} is not on screen")
                self.assertLessEqual(abs(x - expected[0]), TOLERANCE_PX, (x, y, expected))
                self.assertLessEqual(abs(y - expected[1]), TOLERANCE_PX, (x, y, expected))
                checked += 1
        self.assertGreaterEqual(checked, 4)

    def test_3_playing_advances_time(self):
        self.viewer("seek(1.0)")
        self.viewer("play()")
        time.sleep(0.5)
        now, playing = self.viewer("time()"), self.viewer("playing()")
        self.viewer("pause()")
        self.assertTrue(playing)
        self.assertGreater(now, 1.1)
        self.assertLess(now, 3.0)
        self.keep(self.page.screenshot(), "playing.png")

    def test_4_the_energy_plot_shows_the_csv_drift(self):
        error = energy_error(self.trajectory.energy)
        self.page.evaluate("document.getElementById('series').value = '0'")
        self.viewer("seek(5.0)")
        plot = self.viewer("plot()")
        self.assertEqual(plot["label"], error.label)
        self.assertAlmostEqual(plot["worst"] / error.worst, 1.0, places=6)
        self.assertAlmostEqual(plot["hi"] / max(error.values), 1.0, places=6)
        self.assertAlmostEqual(plot["lo"] / min(error.values), 1.0, places=6)
        png = self.page.screenshot()
        self.keep(png, "energy_plot.png")
        # the curve reaches the plot's top and bottom edges: its extremes are drawn
        left, top = plot["left"], plot["top"]
        right, bottom = left + plot["width"], top + plot["height"]
        for edge in (top, bottom):
            near_edge = (left, edge - 3, right, edge + 3)
            _, _, count = colour_centroid(png, (0x1f, 0x77, 0xb4), near_edge, tolerance=40)
            self.assertGreater(count, 0, f"no curve near y = {edge}")


if __name__ == "__main__":
    unittest.main()
