# SPDX-License-Identifier: BSD-3-Clause
"""The sweep file: its form and names checked with errors that name the file, the line and the
key; the samples expanded in their documented order; the table written deterministically."""

from __future__ import annotations

import math
import random
import shutil
import tempfile
import unittest
from pathlib import Path
from unittest import mock

from gencoord.sweep import event, preflight, samples, spec, table
from gencoord.sweep.source import SweepFileError, read_source
from gencoord.tool.errors import ToolError

REPOSITORY = Path(__file__).resolve().parents[2]
MODEL = REPOSITORY / "models" / "double_pendulum.py"
COORDINATES = ["theta1", "theta2"]
PARAMETERS = ["l1", "l2", "m1", "m2", "g"]

GOOD = f"""\
# a small grid
[model]
file = "{MODEL}"
parameters = {{ g = 9.81 }}

[integration]
integrator = "rk4"
dt = 0.01
t_end = 2.0

[event]
when = "abs(theta1) > pi or abs(theta2) > pi"

[samples]
method = "grid"
chunk = 4

[samples.q]
theta1 = {{ from = "-pi", to = "pi", points = 3 }}
theta2 = {{ values = [0.0, 0.5] }}

[record]
trajectory_every = 50
"""


class SweepFileTest(unittest.TestCase):

    def setUp(self):
        self.scratch = tempfile.TemporaryDirectory(prefix="gencoord-sweep-file-")
        self.folder = Path(self.scratch.name)

    def tearDown(self):
        self.scratch.cleanup()

    def write(self, text: str, name: str = "sweep.toml") -> str:
        path = self.folder / name
        path.write_text(text, encoding="utf-8")
        return str(path)

    def parse(self, text: str) -> spec.Sweep:
        sweep = spec.parse(read_source(self.write(text)))
        return spec.check_names(sweep, COORDINATES, PARAMETERS)

    def assertFileError(self, text: str, line: int | None, key: str, *phrases: str):
        with self.assertRaises(SweepFileError) as caught:
            self.parse(text)
        message = str(caught.exception)
        where = str(self.folder / "sweep.toml") + (f":{line}" if line else "")
        self.assertTrue(message.startswith(f"{where}: error: {key}"), message)
        self.assertNotIn("\n", message)
        for phrase in phrases:
            self.assertIn(phrase, message)

    def replaced(self, old: str, new: str) -> str:
        self.assertIn(old, GOOD)
        return GOOD.replace(old, new)

    # --- a good file ---------------------------------------------------------------------
    def test_good_grid_is_read_in_full(self):
        sweep = self.parse(GOOD)
        self.assertEqual(sweep.name, "sweep")
        self.assertEqual(sweep.model_file, str(MODEL))
        self.assertEqual((sweep.integrator, sweep.dt, sweep.t_end, sweep.steps),
                         ("rk4", 0.01, 2.0, 200))
        self.assertEqual(sweep.count, 6)
        self.assertEqual(sweep.chunk, 4)
        self.assertEqual(sweep.parameters, {"g": 9.81})
        self.assertEqual([v.label for v in sweep.variables], ["q.theta1", "q.theta2"])
        self.assertEqual(sweep.record, spec.Record(final_state=True, energy_drift=True,
                                                   event_time=True, trajectory_every=50))
        clauses = sweep.event.clauses
        self.assertEqual([(c.kind, c.coordinate, c.absolute, c.op, c.value) for c in clauses],
                         [("q", "theta1", True, ">", math.pi),
                          ("q", "theta2", True, ">", math.pi)])
        self.assertTrue(sweep.event.stop)

    def test_grid_order_first_variable_slowest_and_exact_ends(self):
        rows = list(samples.rows(self.parse(GOOD)))
        self.assertEqual(rows, [(-math.pi, 0.0), (-math.pi, 0.5), (0.0, 0.0), (0.0, 0.5),
                                (math.pi, 0.0), (math.pi, 0.5)])

    def test_grid_points_as_linspace(self):
        sweep = self.parse(self.replaced('from = "-pi", to = "pi", points = 3',
                                         "from = 0, to = 1, points = 11"))
        values = sweep.variables[0].values
        self.assertEqual(values, tuple(0 + k * 0.1 for k in range(10)) + (1.0,))

    def test_event_forms(self):
        clauses = event.parse_condition("pi < theta1 or theta2_dot <= -2*pi or energy > 1")
        self.assertEqual([(c.name, c.absolute, c.op, c.value) for c in clauses],
                         [("theta1", False, ">", math.pi), ("theta2_dot", False, "<=",
                                                            -2 * math.pi),
                          ("energy", False, ">", 1.0)])
        resolved = [event.resolve(c, COORDINATES, event.velocity_names(COORDINATES))
                    for c in clauses]
        self.assertEqual([(c.kind, c.coordinate) for c in resolved],
                         [("q", "theta1"), ("v", "theta2"), ("energy", "")])

    def test_a_model_with_generalized_speeds_names_its_velocities_by_its_speeds(self):
        # a free trunk (position, quaternion; twist) and a hinge: nq = 8, nv = 7
        coordinates = ["trunk_x", "trunk_y", "trunk_z", "trunk_qw", "trunk_qx", "trunk_qy",
                       "trunk_qz", "hinge"]
        speeds = ["trunk_vx", "trunk_vy", "trunk_vz", "trunk_wx", "trunk_wy", "trunk_wz",
                  "hinge"]
        text = GOOD.replace("theta1", "trunk_qx").replace("theta2", "hinge").replace(
            "[record]", "[samples.v]\ntrunk_wz = { values = [1.0, 2.0] }\n\n[record]").replace(
            "abs(hinge) > pi", "abs(trunk_wz) > 3 or hinge_dot < -1")
        sweep = spec.check_names(spec.parse(read_source(self.write(text))), coordinates,
                                 PARAMETERS, speeds)
        self.assertEqual([(v.kind, v.name) for v in sweep.variables],
                         [("q", "trunk_qx"), ("q", "hinge"), ("v", "trunk_wz")])
        self.assertEqual([(c.kind, c.coordinate) for c in sweep.event.clauses],
                         [("q", "trunk_qx"), ("v", "trunk_wz"), ("v", "hinge")])
        wrong = text.replace("[samples.v]\ntrunk_wz", "[samples.v]\ntrunk_qw")
        with self.assertRaises(SweepFileError) as caught:
            spec.check_names(spec.parse(read_source(self.write(wrong))), coordinates,
                             PARAMETERS, speeds)
        self.assertIn("has no speed 'trunk_qw' (it has trunk_vx", str(caught.exception))
        # q 8 and v 7 doubles: at the end and at each of the 5 trajectory points
        self.assertEqual(spec.result_bytes(sweep, 8, 7) - spec.result_bytes(sweep, 8, 8),
                         -8 * (1 + 5))

    # --- random samples ------------------------------------------------------------------
    def random_file(self, method: str, seed: int = 7, count: int = 20) -> str:
        return self.replaced(
            'method = "grid"\nchunk = 4\n\n[samples.q]\n'
            'theta1 = { from = "-pi", to = "pi", points = 3 }\n'
            'theta2 = { values = [0.0, 0.5] }',
            f'method = "{method}"\ncount = {count}\nseed = {seed}\n\n[samples.q]\n'
            'theta1 = { from = -1, to = 1 }\n\n[samples.parameters]\n'
            'm2 = { from = 0.5, to = 2.0 }')

    def test_monte_carlo_is_the_documented_draw(self):
        rows = list(samples.rows(self.parse(self.random_file("monte_carlo"))))
        rng = random.Random(7)
        expected = [(-1 + 2 * rng.random(), 0.5 + 1.5 * rng.random()) for _ in range(20)]
        self.assertEqual(rows, expected)

    def test_latin_hypercube_fills_every_stratum_once(self):
        sweep = self.parse(self.random_file("latin_hypercube", count=50))
        rows = list(samples.rows(sweep))
        self.assertEqual(len(rows), 50)
        for column, (low, high) in enumerate([(-1.0, 1.0), (0.5, 2.0)]):
            strata = sorted(int((row[column] - low) / (high - low) * 50) for row in rows)
            self.assertEqual(strata, list(range(50)))
        self.assertEqual(rows, list(samples.rows(sweep)))  # the same every time
        other = self.parse(self.random_file("latin_hypercube", seed=8, count=50))
        self.assertNotEqual(rows, list(samples.rows(other)))

    # --- the table -------------------------------------------------------------------------
    def test_table_is_deterministic_and_carries_its_digest(self):
        sweep = self.parse(GOOD)
        text = table.table_text(sweep, "double_pendulum", "entry", "// banner")
        self.assertEqual(text, table.table_text(sweep, "double_pendulum", "entry", "// banner"))
        lines = text.splitlines()
        self.assertEqual(lines[0], table.FORMAT)
        self.assertTrue(lines[1].startswith("digest "))
        self.assertIn("event_clause q theta1 1 > 3.141592653589793", lines)
        self.assertIn("samples 6", lines)
        self.assertEqual(lines[-6:], [f"{a!r} {b!r}" for a, b in samples.rows(sweep)])
        changed = table.table_text(sweep, "double_pendulum", "another entry", "// banner")
        self.assertNotEqual(changed.splitlines()[1], lines[1])
        path = self.folder / "t.table"
        table.write_table(str(path), text)
        self.assertEqual(path.read_text(encoding="utf-8"), text)
        self.assertFalse((self.folder / "t.table.partial").exists())

    # --- bad files: each error names the file, the line and the key ----------------------
    def test_toml_syntax_error_names_its_line(self):
        self.assertFileError(self.replaced("dt = 0.01", "dt = = 0.01"), 8, "", "TOML")

    def test_not_utf8(self):
        (self.folder / "sweep.toml").write_bytes(b"[model]\nfile = '\xff'\n")
        with self.assertRaises(SweepFileError) as caught:
            spec.parse(read_source(str(self.folder / "sweep.toml")))
        self.assertIn("not UTF-8", str(caught.exception))

    def test_unknown_keys(self):
        self.assertFileError(GOOD + "[output]\nfile = 'x'\n", 24, "output", "unknown key")
        self.assertFileError(self.replaced("dt = 0.01", "dt = 0.01\nsteps = 3"), 9,
                             "integration.steps", "takes integrator, dt, t_end")
        self.assertFileError(self.replaced("points = 3", "points = 3, step = 1"), 19,
                             "samples.q.theta1.step", "takes from, to, points, values")

    def test_model_file(self):
        self.assertFileError(self.replaced(f'file = "{MODEL}"', 'file = "nowhere.py"'), 3,
                             "model.file", "no such file", "relative to the sweep file")
        self.assertFileError(self.replaced(f'file = "{MODEL}"\n', ""), 2, "model",
                             "needs 'file'")

    def test_integration(self):
        self.assertFileError(self.replaced('"rk4"', '"rk5"'), 7, "integration.integrator",
                             "one of forward_euler")
        self.assertFileError(self.replaced("dt = 0.01", "dt = -0.01"), 8, "integration.dt",
                             "positive")
        self.assertFileError(self.replaced("t_end = 2.0", "t_end = 2.005"), 9,
                             "integration.t_end", "whole number of steps")
        self.assertFileError(self.replaced("dt = 0.01", 'dt = "0.01 s"'), 8, "integration.dt",
                             "not a number")
        self.assertFileError(self.replaced("dt = 0.01", 'dt = "pj/100"'), 8, "integration.dt",
                             "unknown name 'pj'")
        self.assertFileError(self.replaced("dt = 0.01", "dt = true"), 8, "integration.dt",
                             "expects a number")
        self.assertFileError(self.replaced("dt = 0.01", 'dt = "(-8)**(1/3)"'), 8,
                             "integration.dt", "not a real number")
        # found by tests/properties/test_sweep_fuzz.py: t_end / dt overflows, and an integer
        # no double holds
        self.assertFileError(self.replaced("t_end = 2.0", "t_end = 1e308"), 8,
                             "integration.dt", "inf steps")
        self.assertFileError(self.replaced("dt = 0.01", f'dt = "{"1" * 400}"'), 8,
                             "integration.dt", "(400 digits) is too large for a double")

    def test_event(self):
        self.assertFileError(self.replaced("or abs", "and abs"), 12, "event.when",
                             "only 'or'")
        self.assertFileError(self.replaced("abs(theta1) > pi or ", "0 < theta1 < 1 or "), 12,
                             "event.when", "one comparison")
        self.assertFileError(self.replaced("abs(theta1) > pi or ", "sin(theta1) > 0 or "), 12,
                             "event.when", "one side must be")
        self.assertFileError(self.replaced("abs(theta1)", "abs(theta3)"), 12, "event.when",
                             "'theta3' is not a coordinate", "theta1_dot")
        self.assertFileError(self.replaced('when = "abs(theta1) > pi or abs(theta2) > pi"',
                                           "stop = false"), 11, "event", "needs 'when'")
        self.assertFileError(self.replaced("[event]\nwhen", "[event]\nstop = 1\nwhen"), 12,
                             "event.stop", "true or false")

    def test_samples(self):
        self.assertFileError(self.replaced("points = 3", "points = 0"), 19,
                             "samples.q.theta1.points", "whole number >= 1")
        self.assertFileError(self.replaced("points = 3", "points = 1.5"), 19,
                             "samples.q.theta1.points", "whole number >= 1")
        self.assertFileError(self.replaced(", points = 3", ""), 19, "samples.q.theta1",
                             "needs 'points'")
        self.assertFileError(self.replaced('method = "grid"', 'method = "sobol"'), 15,
                             "samples.method", "grid, latin_hypercube, monte_carlo")
        self.assertFileError(self.replaced('method = "grid"', 'method = "grid"\nseed = 1'), 16,
                             "samples.seed", "a grid has no count or seed")
        self.assertFileError(self.replaced("theta2 = {", "theta3 = {"), 20,
                             "samples.q.theta3", "has no coordinate 'theta3'", "theta1, theta2")
        self.assertFileError(self.replaced("values = [0.0, 0.5]", "values = []"), 20,
                             "samples.q.theta2.values", "non-empty list")
        no_samples = GOOD.split("[samples.q]")[0] + "[record]\n"
        self.assertFileError(no_samples, 14, "samples", "samples nothing")

    def test_a_chunk_fits_one_mpi_message(self):
        text = GOOD
        for old, new in (("points = 3", "points = 1000"), ("chunk = 4", "chunk = 1000"),
                         ("t_end = 2.0", "t_end = 1000.0"),
                         ("trajectory_every = 50", "trajectory_every = 1")):
            text = text.replace(old, new)
        # 100001 trajectory points of q and v (2 x 2 doubles) per sample: 3.2 MB a sample
        self.assertFileError(text, 16, "samples.chunk", "more than one MPI message holds",
                             "set chunk <= 671")

    def test_the_results_file_size_is_estimated_and_checked_against_free_space(self):
        sweep = self.parse(GOOD)  # 6 samples of 2 variables; 5 trajectory points of q and v
        per_sample = 16 + 1 + 8 + 64 + (8 + 32) + 8 + 8 + 5 * 32
        self.assertEqual(preflight.results_bytes(sweep, 2, 2),
                         6 * per_sample + 5 * 8 + 2 + preflight.METADATA)
        self.assertEqual(preflight.summary(sweep, 2, 2), "gencoord: sweep: 6 samples x 200 steps "
                         "(1,200 steps in all), results file about 1.05 MB")
        preflight.check_disk(sweep, 2, 2, str(self.folder))  # this disk has a megabyte free
        full = mock.Mock(return_value=shutil._ntuple_diskusage(10**9, 10**9 - 5000, 5000))
        with mock.patch.object(preflight.shutil, "disk_usage", full):
            with self.assertRaises(ToolError) as caught:
                preflight.check_disk(sweep, 2, 2, "out")
            self.assertEqual(str(caught.exception),
                             "the results file of sweep would take about 1.05 MB, but the disk "
                             "of out has 5 kB free; free some space, record less (fewer "
                             "samples, a larger trajectory_every, no trajectory) or give "
                             "another --output-dir")
            preflight.check_disk(sweep, 2, 2, "out", replaced=2 * 10**6)  # --overwrite frees it

    def test_random_samples_need_count_and_seed(self):
        text = self.random_file("monte_carlo").replace("seed = 7\n", "")
        self.assertFileError(text, 14, "samples", "needs 'seed'")
        self.assertFileError(self.random_file("monte_carlo").replace("to = 1 }", "to = -2 }"),
                             20, "samples.q.theta1.to", "to >= from")
        self.assertFileError(self.random_file("latin_hypercube").replace(
            "from = -1, to = 1", "from = -1, to = 1, points = 3"), 20,
            "samples.q.theta1.points", "unknown key", "takes from, to")

    def test_numbers_a_double_cannot_hold(self):
        self.assertFileError(self.replaced("points = 3", "points = 1000000000000"), 19,
                             "samples.q.theta1.points", "more than the 100000000 samples")
        huge = self.replaced('from = "-pi", to = "pi", points = 3',
                             "from = -1e308, to = 1e308, points = 3")
        self.assertFileError(huge, 19, "samples.q.theta1", "spacing overflows")
        wide = self.random_file("monte_carlo").replace("from = -1, to = 1",
                                                       "from = -1e308, to = 1e308")
        self.assertFileError(wide, 20, "samples.q.theta1", "wider than a double holds")
        seeded = self.random_file("monte_carlo").replace("seed = 7", f"seed = {2**63}")
        self.assertFileError(seeded, 17, "samples.seed", "at most 2^63 - 1")
        nested = self.replaced("dt = 0.01", 'dt = "' + "(" * 5000 + "0.01" + ")" * 5000 + '"')
        self.assertFileError(nested, 8, "integration.dt", "characters")
        deep = self.replaced("dt = 0.01", 'dt = "' + "-" * 995 + '0.01"')
        self.assertFileError(deep, 8, "integration.dt", "nested too deeply")
        tiny = self.replaced("dt = 0.01", "dt = 1e-12")
        self.assertFileError(tiny, 8, "integration.dt", "2e+12 steps", "raise dt")

    def test_names(self):
        self.assertFileError(self.replaced("g = 9.81", "gravity = 9.81"), 4,
                             "model.parameters.gravity", "has no parameter 'gravity'",
                             "l1, l2, m1, m2, g")
        self.assertFileError(GOOD + "[initial]\nq = { phi = 1 }\n", 25, "initial.q.phi",
                             "has no coordinate 'phi'")

    def test_record(self):
        self.assertFileError(self.replaced("trajectory_every = 50", "trajectory_every = 201"),
                             23, "record.trajectory_every", "more than the run's 200")
        without_event = GOOD.replace('[event]\nwhen = "abs(theta1) > pi or abs(theta2) > pi"\n',
                                     "")
        self.assertFileError(without_event + "event_time = true\n", 22, "record.event_time",
                             "there is no [event]")
        sweep = self.parse(without_event)
        self.assertFalse(sweep.record.event_time)
        self.assertIsNone(sweep.event)


if __name__ == "__main__":
    unittest.main()
