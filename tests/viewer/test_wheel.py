# SPDX-License-Identifier: BSD-3-Clause
"""A rolling wheel in a real browser (headless Chromium): the rolling disk's page, on a
trajectory written here (the disk upright, rolling along x), draws the wheel as a disk of its
radius in its own plane. Points of the wheel's plane inside its rim change colour when the
wheel's shape is hidden and shown; points of the plane outside the rim do not.

GENCOORD_SKIP_BROWSER=1 skips it, as test_browser.py."""

from __future__ import annotations

import csv
import json
import math
import os
import tempfile
import unittest

from gencoord.viewer import page
from gencoord.viewer.headless import Browser, find_chromium
from gencoord.viewer.in_browser import open_viewer
from gencoord.viewer.png import read_png

from .trajectory import REPOSITORY

SCENE = os.path.join(REPOSITORY, "generated", "rolling_disk.scene.json")
RADIUS, SPEED = 0.3, 0.5  # m, m/s: the model's default radius
WIDTH, HEIGHT = 900, 650


def rolling_csv(path: str, scene: dict) -> None:
    """The disk upright on the ground, its contact point moving along x at SPEED: the point
    masses at centre + R offset, R the spin about the axle (y)."""
    offsets = scene["bodies"][0]["offsets"]
    names = scene["bodies"][0]["points"]
    header = (["t"] + [f"q_{c}" for c in ("x", "y", "psi", "phi", "theta")]
              + [f"v_{c}" for c in ("x", "y", "psi", "phi", "theta")] + ["energy"]
              + [f"{n}_{a}" for n in names for a in "xyz"])
    with open(path, "w", newline="", encoding="utf-8") as handle:
        out = csv.writer(handle)
        out.writerow(header)
        for k in range(201):
            t = k * 0.01
            x, spin = SPEED * t, SPEED * t / RADIUS
            c, s = math.cos(spin), math.sin(spin)
            row = [t, x, 0, 0, 0, spin, SPEED, 0, 0, 0, SPEED / RADIUS, 1.0]
            for r in offsets:  # rotation about y by the spin
                row += [x + c * r[0] + s * r[2], r[1], RADIUS - s * r[0] + c * r[2]]
            out.writerow(row)


def pixel(png_rows, channels: int, x: float, y: float):
    row = png_rows[int(y)]
    return row[int(x) * channels:int(x) * channels + 3]


@unittest.skipIf(os.environ.get("GENCOORD_SKIP_BROWSER") == "1", "GENCOORD_SKIP_BROWSER=1")
class WheelTest(unittest.TestCase):

    def test_the_wheel_is_a_disk_of_its_radius_in_its_plane(self):
        if not find_chromium():
            raise AssertionError("no Chromium: run scripts/setup.sh --browser")
        folder = os.environ.get("GENCOORD_VIEWER_ARTIFACTS") or tempfile.mkdtemp(
            prefix="gencoord-viewer-")
        os.makedirs(folder, exist_ok=True)
        with open(SCENE, encoding="utf-8") as handle:
            scene = json.load(handle)
        trajectory = os.path.join(folder, "rolling_disk.csv")
        rolling_csv(trajectory, scene)
        html = os.path.join(folder, "rolling_disk.html")
        page.write_page(trajectory, scene, html, "rolling_disk")
        with Browser(width=WIDTH, height=HEIGHT) as browser:
            view = open_viewer(browser, html)
            view.evaluate("gencoordViewer.setTrails(false)")
            t = 1.0
            view.evaluate(f"gencoordViewer.seek({t})")
            centre = (SPEED * t, 0.0, RADIUS)
            shots = {}
            for shown in (True, False):
                self.assertTrue(view.evaluate(
                    f"gencoordViewer.showBody('disk', {'true' if shown else 'false'})"))
                shots[shown] = view.screenshot()
            with open(os.path.join(folder, "rolling_disk_wheel.png"), "wb") as handle:
                handle.write(shots[True])

            def screen(x, y, z):
                return view.evaluate(f"gencoordViewer.project({x!r}, {y!r}, {z!r})")

            _, _, channels, with_wheel = read_png(shots[True])
            _, _, _, without = read_png(shots[False])

            def covered(point) -> bool:
                x, y = screen(*point)
                a, b = pixel(with_wheel, channels, x, y), pixel(without, channels, x, y)
                return sum(abs(a[i] - b[i]) for i in range(3)) > 30

            # in the wheel's plane (x, z), off the body frame's axes: 45 degrees around
            for angle in (45, 135, 225, 315):
                a = math.radians(angle)
                for fraction, inside in ((0.6, True), (0.9, True), (1.25, False)):
                    point = (centre[0] + fraction * RADIUS * math.cos(a), 0.0,
                             centre[2] + fraction * RADIUS * math.sin(a))
                    if point[2] < 0:
                        continue  # below the ground
                    with self.subTest(angle=angle, fraction=fraction):
                        self.assertEqual(covered(point), inside, point)
            self.assertEqual(view.console_errors, [])


if __name__ == "__main__":
    unittest.main()
