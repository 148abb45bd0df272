# SPDX-License-Identifier: BSD-3-Clause
"""A deformable run's page (gencoord/viewer/deformable.py): the frames and springs the demo
writes, read with errors that name the file and line; in headless Chromium, a spring is drawn
until the time it broke."""

from __future__ import annotations

import array
import base64
import os
import shutil
import tempfile
import unittest

from gencoord.tool.errors import ToolError
from gencoord.viewer import page
from gencoord.viewer.deformable import deformable_data
from gencoord.viewer.headless import Browser, find_chromium
from gencoord.viewer.in_browser import open_viewer

# a square of four nodes with both diagonals; the diagonal 0-2 breaks at t = 0.5
FRAMES = [(0.0, [(0, 0), (1, 0), (1, 1), (0, 1)]),
          (0.25, [(0, -0.1), (1, -0.1), (1, 0.9), (0, 0.9)]),
          (1.0, [(0, -0.4), (1.2, -0.4), (1.2, 0.6), (0, 0.6)])]
SPRINGS = [(0, 1, ""), (1, 2, ""), (2, 3, ""), (3, 0, ""), (0, 2, "0.5"), (1, 3, "")]


def write_run(folder: str, frames=FRAMES, springs=SPRINGS, frames_header="frame,time,node,x,y"):
    with open(os.path.join(folder, "frames.csv"), "w", encoding="utf-8") as handle:
        handle.write(frames_header + "\n")
        for f, (t, nodes) in enumerate(frames):
            for n, (x, y) in enumerate(nodes):
                handle.write(f"{f},{t},{n},{x},{y}\n")
    with open(os.path.join(folder, "springs.csv"), "w", encoding="utf-8") as handle:
        handle.write("spring,i,j,broken_at\n")
        for k, (i, j, broken) in enumerate(springs):
            handle.write(f"{k},{i},{j},{broken}\n")


def decoded(text: str, kind: str) -> list:
    return list(array.array(kind, base64.b64decode(text)))


class DeformableDataTest(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="gencoord-deformable-")
        self.addCleanup(shutil.rmtree, self.folder, ignore_errors=True)

    def test_frames_and_springs(self):
        write_run(self.folder)
        data = deformable_data(self.folder)
        self.assertEqual((data["frames"], data["stride"]), (3, 1))
        self.assertEqual(data["points"], ["0", "1", "2", "3"])
        self.assertEqual(data["mesh"], {"springs": 6, "broken": 1})
        self.assertEqual(decoded(data["arrays"]["t"], "d"), [0.0, 0.25, 1.0])
        positions = decoded(data["arrays"]["positions"], "f")
        last = [c for node in FRAMES[-1][1] for c in node]
        for got, want in zip(positions[-8:], last, strict=True):
            self.assertAlmostEqual(got, want, places=6)
        pairs = decoded(data["arrays"]["spring_nodes"], "i")
        broken_at = decoded(data["arrays"]["broken_at"], "d")
        self.assertEqual(broken_at[-1], 0.5, "the broken spring comes last")
        self.assertEqual(pairs[-2:], [0, 2])
        self.assertEqual(sorted(zip(pairs[::2], pairs[1::2])),
                         sorted((i, j) for i, j, _ in SPRINGS))

    def test_a_wrong_header_names_the_file_and_line(self):
        write_run(self.folder, frames_header="frame,t,node,x,y")
        with self.assertRaisesRegex(ToolError, r"frames\.csv:1: expected the header"):
            deformable_data(self.folder)

    def test_a_spring_to_a_missing_node_names_its_line(self):
        write_run(self.folder, springs=[*SPRINGS, (0, 9, "")])
        with self.assertRaisesRegex(ToolError, r"springs\.csv:8: node 9 does not exist"):
            deformable_data(self.folder)

    def test_a_missing_run_says_how_to_make_one(self):
        with self.assertRaisesRegex(ToolError, "frames.csv: no such file; run "
                                               "deformable_demo"):
            deformable_data(self.folder)


@unittest.skipIf(os.environ.get("GENCOORD_SKIP_BROWSER") == "1", "GENCOORD_SKIP_BROWSER=1")
class DeformablePageTest(unittest.TestCase):
    def test_a_spring_is_drawn_until_it_breaks(self):
        self.assertTrue(find_chromium(), "no Chromium: run scripts/setup.sh --browser")
        with tempfile.TemporaryDirectory() as folder:
            write_run(folder)
            html = os.path.join(folder, "frames.html")
            page.write_data_page(deformable_data(folder), html, "square")
            with Browser(width=800, height=600) as browser:
                viewer = open_viewer(browser, html)
                drawn = {t: viewer.evaluate(f"gencoordViewer.seek({t}); "
                                            f"gencoordViewer.springsDrawn()")
                         for t in (0.0, 0.4999, 0.5, 1.0)}
                plot = viewer.evaluate("gencoordViewer.plot()")
                errors = viewer.console_errors
        self.assertEqual(drawn, {0.0: 6, 0.4999: 6, 0.5: 5, 1.0: 5})
        self.assertEqual(plot["label"], "springs intact")
        self.assertEqual((plot["lo"], plot["hi"]), (5, 6))
        self.assertEqual(errors, [])


if __name__ == "__main__":
    unittest.main()
