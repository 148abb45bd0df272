# SPDX-License-Identifier: BSD-3-Clause
"""The viewer page without a browser (gencoord/viewer/page.py): it carries everything it needs
and nothing from the network, holds the trajectory exactly enough, stays light, and thins a
long trajectory without hiding its worst energy error."""

from __future__ import annotations

import array
import base64
import json
import os
import re
import tempfile
import unittest
from unittest import mock

from gencoord.tool.errors import ToolError
from gencoord.tool.trajectory_svg import read_trajectory
from gencoord.viewer import page, three_js

from .trajectory import double_pendulum_csv, double_pendulum_scene


def decoded(text: str, kind: str) -> list[float]:
    return list(array.array(kind, base64.b64decode(text)))


def embedded_data(html: str) -> dict:
    match = re.search(r'<script type="application/json" id="gencoord-data">(.*?)</script>',
                      html, re.DOTALL)
    return json.loads(match.group(1).replace("<\\/", "</"))


class PageTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.csv = double_pendulum_csv()
        cls.html = page.page_html(page.page_data(cls.csv, double_pendulum_scene()),
                                  "double_pendulum")

    def test_nothing_is_fetched(self):
        self.assertNotRegex(self.html, r"<script[^>]*\ssrc=")
        self.assertNotRegex(self.html, r"<link[^>]*\shref=")
        import_map = json.loads(re.search(r'<script type="importmap">(.*?)</script>',
                                          self.html, re.DOTALL).group(1))
        self.assertEqual(sorted(import_map["imports"]),
                         ["three", "three/addons/controls/OrbitControls.js"])
        for url in import_map["imports"].values():
            self.assertTrue(url.startswith("data:text/javascript;base64,"))
        library = base64.b64decode(import_map["imports"]["three"].split(",", 1)[1]).decode()
        self.assertEqual(library, three_js.sources()["three"])  # the pinned, verified one

    def test_ten_seconds_at_one_kilohertz_stay_under_two_megabytes(self):
        self.assertLess(len(self.html.encode()), 2_000_000)

    def test_the_page_holds_the_trajectory(self):
        data = embedded_data(self.html)
        trajectory = read_trajectory(self.csv)
        self.assertEqual((data["rows"], data["stride"], data["frames"]), (10001, 1, 10001))
        self.assertEqual(data["points"], ["bob1", "bob2", "fixed:pivot"])
        self.assertEqual(data["coordinates"], ["theta1", "theta2"])
        self.assertEqual(decoded(data["arrays"]["t"], "d"), trajectory.t)
        positions = decoded(data["arrays"]["positions"], "f")
        for row in (0, 1234, 10000):
            for k, point in enumerate(data["points"]):
                for a, axis in enumerate("xy"):
                    self.assertAlmostEqual(positions[(row * 3 + k) * 2 + a],
                                           trajectory.path(point, axis)[row], places=6)
        errors = decoded(data["arrays"]["energy_error"], "f")
        e0 = trajectory.energy[0]
        worst = max(abs(e - e0) / abs(e0) for e in trajectory.energy)
        self.assertAlmostEqual(max(map(abs, errors)) / worst, 1.0, places=6)
        self.assertAlmostEqual(data["energy"]["worst"], worst, delta=1e-15)

    def test_a_long_trajectory_is_thinned_and_keeps_its_worst_energy_error(self):
        rows = 1001
        with tempfile.TemporaryDirectory() as folder:
            csv = os.path.join(folder, "thin.csv")
            with open(csv, "w", encoding="utf-8") as handle:
                handle.write("t,q_a,v_a,energy,p_x,p_y,fixed:o_x,fixed:o_y\n")
                for i in range(rows):
                    energy = 1.0 + (1e-3 if i == 517 else 0.0)  # one spike between kept rows
                    handle.write(f"{i * 0.01},{i},{0},{energy},{i},{-i},0,0\n")
            scene = dict(double_pendulum_scene(), particles=[{"name": "p", "mass": 1.0}],
                         fixed_points=["o"])
            with mock.patch.object(page, "MAX_NUMBERS", 1000):
                data = page.page_data(csv, scene)
        per_row = 2 + 1 + 2 * 2
        self.assertEqual(data["stride"], -(-rows * per_row // 1000))
        t = decoded(data["arrays"]["t"], "d")
        self.assertEqual(t[-1], (rows - 1) * 0.01, "the last state is always kept")
        self.assertEqual(len(t), data["frames"])
        self.assertLessEqual(data["frames"] * per_row, 1000 + per_row)
        self.assertNotIn(517 * 0.01, t)
        self.assertAlmostEqual(max(decoded(data["arrays"]["energy_error"], "f")), 1e-3,
                               places=9)

    def test_a_dissipative_trajectory_carries_the_dampers_work_scaled_as_the_energy(self):
        with tempfile.TemporaryDirectory() as folder:
            csv = os.path.join(folder, "damped.csv")
            with open(csv, "w", encoding="utf-8") as handle:
                handle.write("t,q_a,v_a,energy,work,p_x,p_y,fixed:o_x,fixed:o_y\n")
                for i in range(101):  # E falls from 4 J by W = -0.02 t, to 1e-6 J
                    t = i * 0.01
                    energy = 4.0 - 0.02 * t + (1e-6 if i == 50 else 0.0)
                    handle.write(f"{t},{i},0,{energy},{-0.02 * t},{i},{-i},0,0\n")
            scene = dict(double_pendulum_scene(), particles=[{"name": "p", "mass": 1.0}],
                         fixed_points=["o"], conserves_energy=False)
            data = page.page_data(csv, scene)
        work = decoded(data["arrays"]["work"], "f")
        change = decoded(data["arrays"]["energy_error"], "f")
        self.assertAlmostEqual(work[-1], -0.02 / 4.0, places=7)  # relative to E0, as E - E0
        self.assertAlmostEqual(change[-1], work[-1], places=7)
        self.assertIn("E \u2212 E\u2080 \u2212 W", data["energy"]["summary"])
        self.assertIn(f"{1e-6 / 4:.2e}", data["energy"]["summary"])
        self.assertNotIn("work", page.page_data(self.csv, double_pendulum_scene())["arrays"])

    def test_a_crosscheck_trajectory_puts_the_maximal_model_beside_the_reduced(self):
        with tempfile.TemporaryDirectory() as folder:
            csv = os.path.join(folder, "crosscheck.csv")
            with open(csv, "w", encoding="utf-8") as handle:
                handle.write("t,q_a,v_a,energy,bob_x,bob_y,fixed:pivot_x,fixed:pivot_y,"
                             "maximal:bob_x,maximal:bob_y\n")
                for i in range(11):
                    x, y = 0.1 * i - 0.5, -1.0
                    handle.write(f"{i * 0.1},0,0,1,{x},{y},0,0,{x + 0.01},{y - 0.02}\n")
            scene = dict(double_pendulum_scene(), particles=[{"name": "bob", "mass": 1.0}])
            data = page.page_data(csv, scene)
        self.assertEqual(data["points"], ["bob", "fixed:pivot", "maximal:bob",
                                          "maximal:fixed:pivot"])
        self.assertEqual(data["companion"], "maximal:")
        shift = data["companion_shift"]
        self.assertEqual(shift[1], 0.0, "beside, across the up axis")
        self.assertGreaterEqual(shift[0], 1.3 * 1.0)  # the reduced model spans 1 m in x
        positions = decoded(data["arrays"]["positions"], "f")
        last = positions[10 * 8:]      # the last frame: 4 points x 2
        self.assertAlmostEqual(last[4], 0.5 + 0.01 + shift[0], places=6)
        self.assertAlmostEqual(last[5], -1.02, places=6)
        self.assertAlmostEqual(last[6], shift[0], places=6)  # the pivot's copy
        self.assertAlmostEqual(last[7], 0.0, places=6)

    def test_a_page_is_written_whole_or_not_at_all(self):
        with tempfile.TemporaryDirectory() as folder:
            target = os.path.join(folder, "view.html")
            with mock.patch.object(page, "page_data", side_effect=ValueError("bad row")):
                with self.assertRaises(ValueError):
                    page.write_page(self.csv, double_pendulum_scene(), target, "x")
            self.assertEqual(os.listdir(folder), [])
            page.write_page(self.csv, double_pendulum_scene(), target, "x")
            self.assertEqual(os.listdir(folder), ["view.html"])

    def test_a_csv_that_is_not_this_models_trajectory_is_one_line_naming_it(self):
        scene = double_pendulum_scene()
        cases = {
            "t,q_theta\n0,1\nx,y,z\n": r"bad\.csv:3: 3 values for 2 columns",
            "t,energy\n0,x\n": r"bad\.csv:2: column 'energy': 'x' is not a number",
            "t,q_theta\n0,1\n": r"bad\.csv: no column 'energy'",
            "t,energy,bob1_x\n0,1,2\n": r"bad\.csv: no column 'bob1_y': every point needs",
            "t,energy,foo_x,foo_y\n0,1,2,3\n":
                r"bad\.csv: no position columns of 'bob1' of double_pendulum; is it a trajectory",
            "t,energy,a_x,a_y,a_z\n0,1,2,3,4\n":
                r"bad\.csv: positions in 3D, but double_pendulum is a 2D model",
            "": r"bad\.csv: empty file",
        }
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "bad.csv")
            for text, message in cases.items():
                with self.subTest(text=text):
                    with open(path, "w", encoding="utf-8") as handle:
                        handle.write(text)
                    with self.assertRaisesRegex(ToolError, message) as caught:
                        page.page_data(path, scene)
                    self.assertNotIn("\n", str(caught.exception))


class ThreeJsTest(unittest.TestCase):
    """three.js comes from the cache, else the registry, and only as published."""

    def test_an_unreachable_registry_says_what_to_do(self):
        with tempfile.TemporaryDirectory() as cache, mock.patch.dict(
                os.environ, {"GENCOORD_CACHE_DIR": cache,
                             "GENCOORD_NPM_REGISTRY": "http://127.0.0.1:9"}):
            with self.assertRaisesRegex(ToolError, r"cannot fetch three\.js 0\.170\.0 .*"
                                                   r"npm pack three@0\.170\.0"):
                three_js.sources()
            self.assertEqual(os.listdir(cache), [], "nothing half-written")

    def test_a_tampered_tarball_is_refused(self):
        with tempfile.TemporaryDirectory() as cache, mock.patch.dict(
                os.environ, {"GENCOORD_CACHE_DIR": cache}):
            os.makedirs(os.path.join(cache, "three"))
            with open(os.path.join(cache, "three", f"three-{three_js.VERSION}.tgz"), "wb") as f:
                f.write(b"not three.js")
            with self.assertRaisesRegex(ToolError, "is not three.js .* delete it"):
                three_js.sources()


if __name__ == "__main__":
    unittest.main()
