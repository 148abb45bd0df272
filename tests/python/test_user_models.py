# SPDX-License-Identifier: BSD-3-Clause
"""Model files as a new user writes them (tests/python/user_models/): positions with tan,
1/q and sqrt, larger models whose checks must stay within seconds, and the checks' time
budgets."""

from __future__ import annotations

import tempfile
import textwrap
import time
import unittest
from pathlib import Path
from unittest import mock

import sympy as sp

from gencoord.checks import constraints

from gencoord.checks import redundancy

from gencoord.checks import singularities
from gencoord.checks.budget import Budget, BudgetSpent
from gencoord.derive.dense import Kinematics
from gencoord.errors import ModelError
from gencoord.generate.load import load_model
from gencoord.checks.full_rank import check_full_rank
from gencoord.checks.singularities import analyse_singularities
from gencoord.symbolic.trig_polynomial import vanishes_identically
from gencoord.checks.validate import validate

from .support import describe, run_generate

USER_MODELS = Path(__file__).resolve().parent / "user_models"
CHECKS_SECONDS = 2.0  # CPU seconds for every check of a model of up to 6 coordinates


def load_source(directory: Path, source: str):
    path = directory / "model.py"
    path.write_text(textwrap.dedent(source), encoding="utf-8")
    model, _, _ = load_model(str(path), {})
    return model


def run_checks(model):
    """Every generation-time check, as the pipeline runs them; (report lines, notes)."""
    validate(model)
    kin = Kinematics(model)
    notes = check_full_rank(model, kin=kin) + constraints.verify_constraints(model, kin=kin)
    return analyse_singularities(model, kin=kin), notes


class AlgebraicPositionsTest(unittest.TestCase):

    def test_tan_reciprocal_and_sqrt_positions_generate(self):
        with tempfile.TemporaryDirectory(prefix="gencoord-user-") as scratch:
            result = run_generate(USER_MODELS / "algebraic_positions.py", "-o", scratch)
            self.assertEqual(result.returncode, 0, describe(result))
            self.assertNotIn("Traceback", result.stderr, describe(result))
            self.assertTrue((Path(scratch) / "algebraic_positions.hpp").is_file())

    def test_poles_of_a_rational_jacobian_are_reported(self):
        model, _, _ = load_model(str(USER_MODELS / "algebraic_positions.py"), {})
        report, notes = run_checks(model)
        # d/ds sqrt(1 - s^2) is infinite at s = +-1, d/da tan(a) at cos(a) = 0
        for expected in ("s - 1 = 0 (J is infinite)", "s + 1 = 0 (J is infinite)",
                         "cos(a) = 0 (J is infinite)"):
            self.assertIn(expected, report.singular_sets, report.lines())
        # q is sampled in [-pi, pi]: sqrt(1 - s^2) is not real for |s| > 1
        self.assertRegex("\n".join(report.lines()), r"\d+ of 200 random configurations skipped")
        self.assertGreater(report.samples, 0)

    def test_wrong_rod_is_caught_where_positions_are_finite(self):
        with tempfile.TemporaryDirectory() as scratch:
            model = load_source(Path(scratch), """\
                from gencoord import Model, sqrt
                model = Model(dim=2)
                s = model.coordinate("s", "slider (m)")
                pivot = model.fixed_point("pivot", [0, 0])
                bead = model.particle("bead", mass=1, position=[sqrt(1 - s**2), s])
                model.rod(pivot, bead, 2)
                """)
            with self.assertRaises(ModelError) as caught:
                run_checks(model)
            self.assertIn("rod 'pivot-bead'", str(caught.exception))

    def test_positions_never_finite_in_the_samples_are_noted(self):
        with tempfile.TemporaryDirectory() as scratch:
            model = load_source(Path(scratch), """\
                from gencoord import Model, sqrt
                model = Model(dim=2)
                s = model.coordinate("s", "slider (m)", initial=20)
                pivot = model.fixed_point("pivot", [0, 0])
                bead = model.particle("bead", mass=1, position=[sqrt(s - 10), s])
                model.pin(bead, [sqrt(10), 20])
                """)
            report, notes = run_checks(model)
        text = "\n".join(report.lines() + notes)
        self.assertIn("Rank check skipped", text)
        self.assertIn("Constraint check skipped for pin 'bead'", text)
        self.assertIn("200 of 200 random configurations skipped", text)


class UserModelSpeedTest(unittest.TestCase):

    def test_checks_take_under_two_seconds(self):
        for name in ("triple_pendulum_springs", "body_with_drag", "algebraic_positions"):
            with self.subTest(model=name):
                model, _, _ = load_model(str(USER_MODELS / f"{name}.py"), {})
                self.assertLessEqual(model.nq, 6)
                started = time.process_time()
                run_checks(model)
                self.assertLess(time.process_time() - started, CHECKS_SECONDS)


class BudgetTest(unittest.TestCase):

    def test_interrupting_stops_a_long_computation(self):
        budget = Budget(0.05)
        started = time.process_time()
        with self.assertRaises(BudgetSpent):
            with budget.interrupting():
                while True:
                    sum(range(1000))
        self.assertLess(time.process_time() - started, 1.0)
        self.assertTrue(budget.spent())

    def _double_pendulum(self, scratch: str, rod_length: str):
        return load_source(Path(scratch), f"""\
            from gencoord import Model, cos, sin
            model = Model(dim=2)
            theta = model.coordinate("theta", "angle (rad)")
            phi = model.coordinate("phi", "angle (rad)")
            l = model.parameter("l", 1.0, "length (m)")
            pivot = model.fixed_point("pivot", [0, 0])
            bob = model.particle("bob", mass=1, position=[l * sin(theta), -l * cos(theta)])
            end = model.particle("end", mass=1, position=[l * sin(theta) + sin(phi),
                                                         -l * cos(theta) - cos(phi)])
            model.rod(pivot, bob, {rod_length})
            """)

    def test_spent_budgets_are_reported_in_one_line_each(self):
        with tempfile.TemporaryDirectory() as scratch, \
                mock.patch.object(singularities, "SYMBOLIC_SECONDS", 0.0), \
                mock.patch.object(singularities, "SAMPLING_SECONDS", 0.0), \
                mock.patch.object(redundancy, "SEARCH_SECONDS", 0.0), \
                mock.patch.object(constraints, "PROOF_SECONDS", 0.0):
            report, notes = run_checks(self._double_pendulum(scratch, "l"))
            with self.assertRaises(ModelError):  # no proof, but sampling still refuses it
                run_checks(self._double_pendulum(scratch, "2 * l"))
            with mock.patch.object(constraints, "SAMPLING_SECONDS", 0.0):
                _, sampling_notes = run_checks(self._double_pendulum(scratch, "l"))
        lines = report.lines() + notes + sampling_notes
        for what in ("Symbolic search stopped at its time budget",
                     "Conditioning sampling stopped at its time budget",
                     "Redundancy search stopped at its time budget",
                     "Constraint check stopped at its time budget"):
            self.assertEqual(len([line for line in lines if line.startswith(what)]), 1,
                             f"{what!r} not reported once in:\n" + "\n".join(lines))


class TrigPolynomialTest(unittest.TestCase):

    def test_identities_are_proven_and_non_identities_are_not(self):
        a, b, r, l = sp.symbols("a b r l", real=True)
        proven = [sp.sin(a + b)**2 + sp.cos(a + b)**2 - 1,
                  sp.tan(a) * sp.cos(a) - sp.sin(a),
                  l * sp.sin(a)**2 * sp.cos(b)**2 + l * sp.sin(a)**2 * sp.sin(b)**2
                  + l * sp.cos(a)**2 - l,
                  sp.sqrt(1 + r**2)**2 - 1 - r**2,
                  sp.Float(0.3) * (sp.sin(a)**2 + sp.cos(a)**2) - sp.Float(0.3)]
        for expr in proven:
            self.assertTrue(vanishes_identically(expr), expr)
        for expr in (sp.sin(a), sp.sin(a)**2 + sp.cos(a)**2 - sp.Float(1.0000001), 1 / r):
            self.assertFalse(vanishes_identically(expr), expr)


if __name__ == "__main__":
    unittest.main()
