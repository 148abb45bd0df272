# SPDX-License-Identifier: BSD-3-Clause
"""A robot in a real browser (headless Chromium): the iiwa14 (models/iiwa14.urdf, which has no
<visual> elements) held at a bent pose is drawn as its skeleton, a capsule from each link's
joint to the next. Along every moving link's capsule the picture changes when the links are
hidden and shown; 0.25 m beside the arm it does not. The screenshot is kept with the other
viewer artefacts (GENCOORD_VIEWER_ARTIFACTS).

GENCOORD_SKIP_BROWSER=1 skips it, as test_browser.py."""

from __future__ import annotations

import csv
import os
import tempfile
import unittest


from gencoord import Model, load_urdf
from gencoord.viewer import page
from gencoord.viewer.headless import Browser, find_chromium
from gencoord.viewer.in_browser import open_viewer
from gencoord.viewer.png import read_png
from gencoord.viewer.scene import scene

from .trajectory import REPOSITORY

URDF = os.path.join(REPOSITORY, "models", "iiwa14.urdf")
POSE = [0.3, 0.7, 0.0, -1.1, 0.0, 0.8, 0.0]  # rad: the arm bent, its links apart on screen
WIDTH, HEIGHT = 900, 650


def held_csv(path: str, model: Model, q: list[float]) -> None:
    """Two rows (t = 0 and 1 s) of the arm held at q: its point masses' positions."""
    values = dict(zip((c.symbol for c in model.coordinates), q))
    values.update({p.symbol: p.default for p in model.parameters})
    names = [c.name for c in model.coordinates]
    header = ["t", *(f"q_{n}" for n in names), *(f"v_{n}" for n in names), "energy",
              *(f"{p.name}_{a}" for p in model.particles for a in "xyz")]
    positions = [float(c.xreplace(values)) for p in model.particles for c in p.position]
    with open(path, "w", newline="", encoding="utf-8") as handle:
        out = csv.writer(handle)
        out.writerow(header)
        for t in (0.0, 1.0):
            out.writerow([t, *q, *([0.0] * len(q)), 1.0, *positions])


def pixel(png_rows, channels: int, x: float, y: float):
    row = png_rows[int(y)]
    return row[int(x) * channels:int(x) * channels + 3]


@unittest.skipIf(os.environ.get("GENCOORD_SKIP_BROWSER") == "1", "GENCOORD_SKIP_BROWSER=1")
class RobotTest(unittest.TestCase):

    def test_the_arm_is_drawn_as_its_skeleton(self):
        if not find_chromium():
            raise AssertionError("no Chromium: run scripts/setup.sh --browser")
        folder = os.environ.get("GENCOORD_VIEWER_ARTIFACTS") or tempfile.mkdtemp(
            prefix="gencoord-viewer-")
        os.makedirs(folder, exist_ok=True)
        model = Model(dim=3)
        links = load_urdf(model, URDF)
        drawn = scene(model, "iiwa14")
        trajectory = os.path.join(folder, "iiwa14_held.csv")
        held_csv(trajectory, model, POSE)
        html = os.path.join(folder, "iiwa14_held.html")
        page.write_page(trajectory, drawn, html, "iiwa14")
        values = dict(zip((c.symbol for c in model.coordinates), POSE))
        joints = {name: [float(c) for c in link.frame.origin.xreplace(values)]
                  for name, link in links.items()}
        moving = [body["name"] for body in drawn["bodies"]]
        with Browser(width=WIDTH, height=HEIGHT) as browser:
            view = open_viewer(browser, html)
            view.evaluate("gencoordViewer.setTrails(false)")
            view.evaluate("gencoordViewer.seek(0.5)")
            shots = {}
            for shown in (True, False):
                for name in moving:
                    self.assertTrue(view.evaluate(
                        f"gencoordViewer.showBody('{name}', {'true' if shown else 'false'})"))
                shots[shown] = view.screenshot()
            with open(os.path.join(folder, "iiwa14_skeleton.png"), "wb") as handle:
                handle.write(shots[True])
            _, _, channels, with_links = read_png(shots[True])
            _, _, _, without = read_png(shots[False])

            def covered(point) -> bool:
                x, y = view.evaluate("gencoordViewer.project({}, {}, {})".format(*point))
                a, b = pixel(with_links, channels, x, y), pixel(without, channels, x, y)
                return sum(abs(a[i] - b[i]) for i in range(3)) > 30

            # each moving link's capsule runs from its joint to its child's: one of two points
            # along it is covered (a body frame's axes, drawn over everything, may hide one)
            for name, child in zip(moving, moving[1:]):
                start, end = joints[name], joints[child]
                if sum((e - s) ** 2 for s, e in zip(start, end)) < 1e-6:
                    continue  # the iiwa's wrist joints meet in a point
                along = [[s + f * (e - s) for s, e in zip(start, end)] for f in (0.3, 0.7)]
                with self.subTest(link=name):
                    self.assertTrue(any(covered(p) for p in along), (name, along))
            for name in moving:  # beside the arm, along y
                beside = [joints[name][0], joints[name][1] + 0.25, joints[name][2]]
                with self.subTest(beside=name):
                    self.assertFalse(covered(beside), beside)
            self.assertEqual(view.console_errors, [])


if __name__ == "__main__":
    unittest.main()
