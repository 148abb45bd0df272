# SPDX-License-Identifier: BSD-3-Clause
"""The gencoord command on a model file that lives outside the repository: info, simulate and
crosscheck build, cache and run its programs, write next to the user, and refuse bad input
without a traceback. Builds the programs once (about a minute on 2 cores)."""

from __future__ import annotations

import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[2]
GENCOORD = REPOSITORY / "gencoord"

# A model file that is not one of the repository's models: the consumer example's crane (a
# trolley on a rail held by a spring, a load on a rope), copied into the user's own folder.
CRANE = (REPOSITORY / "examples" / "consumer" / "gantry_crane.py").read_text(encoding="utf-8")


# A free-floating trunk with an arm on a ball joint, spinning and falling: every coordinate
# of both joints is a unit quaternion or a position, every speed a twist component.
TUMBLER = """from gencoord import Ball, Free, Model, Origin, add_link

model = Model(dim=3)
I = [[0.02, 0, 0], [0, 0.03, 0], [0, 0, 0.04]]
trunk = add_link(model, "trunk", None, Free(Origin(xyz=[0, 0, 1])), mass=5.0, inertia=I)
arm = add_link(model, "arm", trunk, Ball(Origin(xyz=[0, 0, -0.2])), mass=1.0, inertia=I,
               com=Origin(xyz=[0, 0.1, -0.3]))
model.gravity([0, 0, -9.81])
"""


# A two-link arm whose shoulder motor, a control input, is rated at 40 N m.
RATED_ARM = """from gencoord import Model, cos, sin
model = Model(dim=2)
a = model.coordinate("shoulder", initial=1.2)
b = model.coordinate("elbow")
u = model.input("u", "shoulder motor torque (N m)")
model.particle("elbow_mass", 1.0, [sin(a), -cos(a)])
model.particle("hand", 1.0, [sin(a) + sin(a + b), -cos(a) - cos(a + b)])
model.gravity([0, -9.81])
model.generalized_force(a, u, name="shoulder motor")
model.limit(a, effort=40.0, name="shoulder motor")
"""

# A four-bar linkage closed by a loop constraint, as a user's own file.
LINKAGE = (REPOSITORY / "models" / "four_bar.py").read_text(encoding="utf-8")

# A pendulum in Cartesian coordinates whose rod is a constraint written in the coordinates:
# the reduced model's alone, with no form in the maximal model's particle positions.
CIRCLE = """from gencoord import Model
model = Model(dim=2)
x = model.coordinate("x", "bob, x (m)", initial=1.0)
y = model.coordinate("y", "bob, y (m)")
model.particle("bob", mass=1.0, position=[x, y])
model.holonomic_constraint(x**2 + y**2 - 1, name="rod")
model.gravity([0, -9.81])
"""


class GencoordCommandTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.scratch = tempfile.TemporaryDirectory(prefix="gencoord-command-")
        cls.home = Path(cls.scratch.name)
        cls.user = cls.home / "project"          # the user's own folder, outside the checkout
        cls.user.mkdir()
        cls.model = cls.user / "crane.py"  # model name: crane
        cls.model.write_text(CRANE, encoding="utf-8")
        # the cache is removed with the scratch folder unless the caller keeps one
        cache = os.environ.get("GENCOORD_TEST_CACHE_DIR") or str(cls.home / "cache")
        if os.environ.get("GENCOORD_TEST_CACHE_DIR"):
            shutil.rmtree(cache, ignore_errors=True)  # every run builds from nothing
        cls.environment = dict(os.environ, PYTHONHASHSEED="0", GENCOORD_CACHE_DIR=cache)

    @classmethod
    def tearDownClass(cls):
        cls.scratch.cleanup()

    def gencoord(self, *arguments: str) -> subprocess.CompletedProcess:
        return subprocess.run([sys.executable, str(GENCOORD), *arguments], cwd=self.user,
                              env=self.environment, capture_output=True, text=True,
                              check=False, timeout=1200)

    def assertSucceeded(self, result):
        self.assertEqual(result.returncode, 0,
                         f"stdout:\n{result.stdout}\nstderr:\n{result.stderr}")

    def assertNoTraceback(self, result):
        self.assertNotIn("Traceback", result.stdout + result.stderr)

    def test_1_simulate_builds_runs_and_writes_next_to_the_user(self):
        result = self.gencoord("simulate", "crane.py", "--duration", "2", "--dt", "1e-3")
        self.assertSucceeded(result)
        self.assertIn("building the simulate program for crane", result.stderr)
        self.assertNotIn("building the crosscheck program", result.stderr)
        with (self.user / "out" / "crane.csv").open(encoding="utf-8") as handle:
            rows = list(csv.DictReader(handle))
        self.assertEqual(len(rows), 2001)
        self.assertAlmostEqual(float(rows[-1]["t"]), 2.0)
        # the wall spring and gravity are conservative: RK4 at 1 ms keeps E to ~1e-9
        drift = float(re.search(r"max \|E - E\(0\)\| = (\S+) J", result.stdout).group(1))
        energy = abs(float(rows[0]["energy"]))
        self.assertLess(drift, 1e-7 * max(energy, 1.0), result.stdout)
        svg = (self.user / "out" / "crane.svg").read_text()
        self.assertTrue(svg.startswith("<svg"))
        self.assertFalse((REPOSITORY / "generated" / "crane.hpp").exists(),
                         "a model outside the checkout was generated into the checkout")

    def test_2_second_run_uses_the_cache(self):
        self.assertSucceeded(self.gencoord("simulate", "crane.py", "--duration", "0.1"))
        result = self.gencoord("simulate", "crane.py", "--duration", "0.1", "--set", "m_load=2")
        self.assertSucceeded(result)
        self.assertNotIn("building", result.stderr)
        if os.path.exists("/dev/full"):  # a full disk: one line with the cause, status 1
            result = self.gencoord("simulate", "crane.py", "--duration", "0.1", "--output",
                                   "/dev/full")
            self.assertEqual(result.returncode, 1, result.stderr)
            self.assertRegex(result.stderr, r"^simulate: error: gencoord: writing '/dev/full' "
                             r"failed: No space left on device; the file is incomplete\n$")

    def test_3_parameters_reach_the_program(self):
        # a rope twice as long swings slower: the load is elsewhere at the end
        ends = []
        for length in ("0.8", "1.6"):
            result = self.gencoord("simulate", "crane.py", "--duration", "1", "--set",
                                   f"l={length}")
            self.assertSucceeded(result)
            ends.append(re.search(r"final q\s+(.*)", result.stdout).group(1))
        self.assertNotEqual(ends[0], ends[1])

    def test_4_crosscheck_converges_with_kappa(self):
        result = self.gencoord("crosscheck", "crane.py", "--kappa", "1e3:1e7", "--t", "1")
        self.assertSucceeded(result)
        slope = float(re.search(r"position error (-?[0-9.]+)", result.stdout).group(1))
        self.assertLess(slope, -0.8, result.stdout)
        self.assertTrue((self.user / "out" / "crane_crosscheck.svg").is_file())
        # the program compiles the maximal model's three integrators, and says so
        refused = self.gencoord("crosscheck", "crane.py", "--integrator", "trapezoidal")
        self.assertEqual(refused.returncode, 2, refused.stderr)
        self.assertIn("crosscheck: error: --integrator trapezoidal: the maximal model runs with "
                      "rk4, symplectic_euler or backward_euler", refused.stderr)

    def test_5_info_describes_the_model(self):
        result = self.gencoord("info", "crane.py")
        self.assertSucceeded(result)
        for expected in ("crane", "nq = 2", "gencoord::models::Crane", "trolley", "rod",
                         "k = 40", "drive force"):
            self.assertIn(expected, result.stdout)

    def test_6_python_builds_a_module_the_user_imports(self):
        # Debian's interpreter: it has NumPy (scripts/setup.sh --python-modules)
        result = self.gencoord("python", "crane.py", "--python", "/usr/bin/python3",
                               "-o", "modules")
        self.assertSucceeded(result)
        module = Path(result.stdout.strip().splitlines()[-1])
        self.assertEqual(module.parent, Path("modules"))
        self.assertTrue((self.user / module).is_file())
        script = ("import crane; p = crane.Params(l=1.6); "
                  "print(crane.nq, crane.coordinate_names, p.l, "
                  "crane.energy(crane.initial_q, crane.initial_v, params=p))")
        imported = subprocess.run(["/usr/bin/python3", "-c", script], cwd=self.user / "modules",
                                  capture_output=True, text=True, check=False)
        self.assertEqual(imported.returncode, 0, imported.stderr)
        self.assertTrue(imported.stdout.startswith("2 ('s', 'theta') 1.6 "), imported.stdout)
        again = self.gencoord("python", "crane.py", "--python", "/usr/bin/python3",
                              "-o", "modules")
        self.assertSucceeded(again)
        self.assertNotIn("building", again.stderr)
        # without --python: the first interpreter that has NumPy, which it names
        chosen = self.gencoord("python", "crane.py", "-o", "chosen")
        self.assertSucceeded(chosen)
        python = re.search(r"built for (\S+) \(Python", chosen.stderr).group(1)
        imported = subprocess.run([python, "-c", "import numpy, crane; print(crane.nq)"],
                                  cwd=self.user / "chosen", capture_output=True, text=True,
                                  check=False)
        self.assertEqual((imported.returncode, imported.stdout), (0, "2\n"), imported.stderr)

    def swing(self, model: str) -> list[float]:
        """The rope angle theta of each row of the model's trajectory."""
        with (self.user / "out" / f"{model}.csv").open(encoding="utf-8") as handle:
            return [float(row["q_theta"]) for row in csv.DictReader(handle)]

    def test_7_a_second_model_recompiles_no_runtime_code(self):
        self.assertSucceeded(self.gencoord("simulate", "crane.py", "--duration", "0.1"))
        trolley = self.user / "trolley.py"
        # the rope's swing from 0.6 rad limited to -0.5 rad on the other side
        trolley.write_text(CRANE.replace("40.0", "41.0") + "model.limit(theta, -0.5, 0.65)\n",
                           encoding="utf-8")
        result = self.gencoord("simulate", "trolley.py", "--duration", "1.5")
        self.assertSucceeded(result)
        self.assertRegex(result.stdout, r"limits +1, reached by theta \(\d+ steps?\)")
        self.assertEqual(min(self.swing("trolley")), -0.5)
        free = self.gencoord("simulate", "trolley.py", "--duration", "1.5", "--no-limits")
        self.assertIn("not enforced (--no-limits)", free.stdout)
        self.assertLess(min(self.swing("trolley")), -0.55)
        outside = self.gencoord("simulate", "trolley.py", "--q", "1.3,0.7")
        self.assertEqual(outside.returncode, 2, outside.stderr)
        self.assertIn("the start puts theta at 0.7, outside its limits [-0.5, 0.65]",
                      outside.stderr)
        self.assertIn("building the simulate program for trolley", result.stderr)
        self.assertNotIn("runtime library", result.stderr)
        logs = list(Path(self.environment["GENCOORD_CACHE_DIR"]).glob("trolley-*/build.log"))
        self.assertEqual(len(logs), 1)
        log = logs[0].read_text(encoding="utf-8")
        self.assertIn("simulate.cpp", log)
        self.assertNotRegex(log, r"runtime/src/\w+\.cpp", "the runtime was compiled again")
        # a motor's rating: the summary names the joint whose input force passed it
        (self.user / "rated.py").write_text(RATED_ARM, encoding="utf-8")
        driven = self.gencoord("simulate", "rated.py", "--duration", "0.2", "--set", "u=50")
        self.assertSucceeded(driven)
        self.assertIn("effort rating exceeded by shoulder motor (inputs' force up to 50, "
                      "rated 40)", driven.stdout)
        gentle = self.gencoord("simulate", "rated.py", "--duration", "0.2", "--set", "u=30")
        self.assertSucceeded(gentle)
        self.assertNotIn("effort rating exceeded", gentle.stdout)

    def test_8_a_free_body_simulates_and_crosschecks_on_its_speeds(self):
        # a free trunk with a ball-jointed arm: unit quaternions, nq = 11, nv = 9
        (self.user / "tumbler.py").write_text(TUMBLER, encoding="utf-8")
        result = self.gencoord("simulate", "tumbler.py", "--duration", "1", "--dt", "1e-3",
                               "--v", "0,0,0,1,2,3,0.5,0,0")
        self.assertSucceeded(result)
        with (self.user / "out" / "tumbler.csv").open(encoding="utf-8") as handle:
            rows = list(csv.DictReader(handle))
        self.assertEqual(len(rows), 1001)
        self.assertIn("v_trunk_wx", rows[0])
        self.assertIn("v_arm_wz", rows[0])
        for row in rows[::100]:
            norm = sum(float(row[f"q_arm_q{c}"]) ** 2 for c in "wxyz")
            self.assertAlmostEqual(norm, 1.0, places=12)
        drift = float(re.search(r"max \|E - E\(0\)\| = (\S+) J", result.stdout).group(1))
        self.assertLess(drift, 1e-7 * max(abs(float(rows[0]["energy"])), 1.0), result.stdout)
        # the penalty model of the same bodies converges to it, from the same spinning start
        checked = self.gencoord("crosscheck", "tumbler.py", "--t", "0.5", "--kappa", "1e3:1e5",
                                "--v", "0,0,0,1,2,3,0.5,0,0")
        self.assertSucceeded(checked)
        self.assertIn("(nq = 11, nv = 9, nx = 24", checked.stdout)
        slope = float(re.search(r"position error (\S+), constraint violation",
                                checked.stdout).group(1))
        self.assertLess(slope, -0.8, checked.stdout)
        refused = self.gencoord("crosscheck", "tumbler.py", "--v", "1,2,3")
        self.assertEqual(refused.returncode, 2, refused.stderr)
        self.assertIn("has 9 generalized speeds; --v needs that many values", refused.stderr)

    def test_9_a_closed_loop_stays_closed_by_projection_or_baumgarte(self):
        (self.user / "linkage.py").write_text(LINKAGE, encoding="utf-8")
        (self.user / "circle.py").write_text(CIRCLE, encoding="utf-8")
        projected = self.gencoord("simulate", "linkage.py", "--duration", "5", "--v", "3,0,0")
        self.assertSucceeded(projected)
        drift = float(re.search(r"max \|C\| and \|A v \+ b\| over the run = (\S+)",
                                projected.stdout).group(1))
        self.assertLess(drift, 1e-10, projected.stdout)
        held = self.gencoord("simulate", "linkage.py", "--duration", "5", "--v", "3,0,0",
                             "--baumgarte", "20")
        self.assertSucceeded(held)
        self.assertIn("(Baumgarte at 20 1/s, no projection)", held.stdout)
        drift = float(re.search(r"max \|C\| and \|A v \+ b\| over the run = (\S+)",
                                held.stdout).group(1))
        self.assertLess(drift, 1e-7, held.stdout)
        for arguments, message in (
                (("simulate", "crane.py", "--baumgarte", "20"),
                 "--baumgarte is for models with kinematic constraints"),
                (("simulate", "linkage.py", "--baumgarte", "-1"), "--baumgarte needs a rate"),
                (("crosscheck", "circle.py"),
                 "holonomic constraint 'rod' (line 6) is written in the coordinates; the "
                 "maximal-coordinate model needs it in the points' positions")):
            with self.subTest(arguments=arguments):
                refused = self.gencoord(*arguments)
                self.assertNotEqual(refused.returncode, 0, refused.stderr)
                self.assertIn(message, refused.stderr)
                self.assertNoTraceback(refused)

    def test_9_a_closed_loop_crosschecks_against_its_penalty_model(self):
        (self.user / "linkage.py").write_text(LINKAGE, encoding="utf-8")
        result = self.gencoord("crosscheck", "linkage.py", "--kappa", "1e4:1e7", "--t", "0.5")
        self.assertSucceeded(result)
        slope = float(re.search(r"position error (-?[0-9.]+)", result.stdout).group(1))
        self.assertLess(slope, -0.8, result.stdout)

    def test_bad_input_is_one_clear_line(self):
        cases = [
            (("simulate", "crane.py", "--set", "nope=1"), r"nope: not an option or a parameter"),
            (("simulate", "missing.py"), r"missing\.py: error: no such model file"),
            (("info", "crane.py", "--set", "L"), r"--set expects name=value"),
            (("python", "crane.py", "--python", "/bin/true"),
             r"^gencoord: error: /bin/true is not a Python interpreter that runs here \(it did "
             r"not answer as Python 3 does\); name one with --python\n$"),
            (("python", "crane.py", "--python", str(REPOSITORY / "README.md")),
             r"README\.md is not a Python interpreter that runs here \(Permission denied\)"),
        ]
        for arguments, message in cases:
            with self.subTest(arguments=arguments):
                result = self.gencoord(*arguments)
                self.assertEqual(result.returncode, 1, result.stderr)
                self.assertRegex(result.stderr, message)
                self.assertNoTraceback(result)

    def test_model_error_names_the_line(self):
        broken = self.user / "broken.py"
        broken.write_text(CRANE.replace("position=[s, 0]", "position=[s, undeclared]"))
        result = self.gencoord("simulate", "broken.py")
        self.assertEqual(result.returncode, 1)
        self.assertRegex(result.stderr, r"broken\.py:\d+: error:")
        self.assertNoTraceback(result)

    def test_cache_key_follows_the_model_file(self):
        from gencoord.tool.driver_build import ModelTarget, entry_dir
        from gencoord.tool.layout import find_layout
        layout = find_layout()
        copy = self.user / "crane_copy.py"

        def key(text: str, options=None) -> str:
            copy.write_text(text)
            return entry_dir(layout, ModelTarget(str(copy), options or {}, "crane", "Crane"))

        original = key(CRANE)
        self.assertEqual(original, key(CRANE))
        self.assertNotEqual(original, key(CRANE.replace("40.0", "41.0")))
        self.assertNotEqual(original, key(CRANE, {"n": "3"}))


if __name__ == "__main__":
    unittest.main()
