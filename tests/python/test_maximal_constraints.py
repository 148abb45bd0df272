# SPDX-License-Identifier: BSD-3-Clause
"""Kinematic constraints in the maximal-coordinate model (derive/maximal_constraints.py).

- On the parameterization (x = X(q), xdot = J v) every maximal row equals the reduced
  model's row, at random q and v: loops written with points (the four-bar, the Delta robot)
  and rolling wheels rebuilt from their point masses (the disk, the bicycle).
- A wheel's contact forces act at its contact point: for a rigid motion of the wheel the
  rate of its contact height is the force direction's product with xdot (the direction is
  the height's gradient, which is what makes the spring conservative for a rigid wheel).
- A row written in the coordinates, or a wheel whose mass lies in one plane, has no maximal
  form, and the reason names the row or the wheel and its line.
"""

from __future__ import annotations

import random
import tempfile
import unittest
from pathlib import Path

import sympy as sp

from gencoord.derive.dense import Kinematics
from gencoord.derive.maximal import MaximalKinematics, derive_maximal, has_maximal_model
from gencoord.derive.maximal_constraints import maximal_constraint_problem, maximal_rows
from gencoord.generate.load import load_model

from .support import MODELS


def _load(name: str):
    return load_model(str(MODELS / f"{name}.py"), None)[0]


def _on_parameterization(model, rng: random.Random):
    """Random q, v, and the maximal x, xdot = X(q), J v, with the parameters' defaults."""
    defaults = {p.symbol: sp.Float(p.default) for p in model.parameters}
    q = {c.symbol: rng.uniform(-0.5, 0.5) for c in model.coordinates}
    v = {c.rate: rng.uniform(-1, 1) for c in model.coordinates}
    maximal = {model.time: 0.3, **{p.symbol: p.default for p in model.parameters}}
    reduced = {**q, **v, **maximal}
    for particle in model.particles:
        position = particle.position.xreplace(defaults)
        rate = [sum(x.diff(c.symbol) * c.rate for c in model.coordinates) for x in position]
        maximal.update(zip(particle.x, [_value(x, reduced) for x in position]))
        maximal.update(zip(particle.xdot, [_value(r, reduced) for r in rate]))
    return {**reduced, **maximal}, maximal


def _value(expr: sp.Expr, values: dict) -> float:
    """expr at `values`, compiled (evalf of the bicycle's rows takes minutes)."""
    symbols = sorted(expr.free_symbols, key=str)
    return float(sp.lambdify(symbols, expr, modules="math")(*[values[s] for s in symbols]))


class MaximalRowsTest(unittest.TestCase):

    def test_maximal_rows_equal_the_reduced_rows_on_the_parameterization(self):
        rng = random.Random(11)
        for name in ("four_bar", "delta_robot", "rolling_disk", "whipple_bicycle"):
            model = _load(name)
            self.assertTrue(has_maximal_model(model), name)
            x = [s for p in model.particles for s in p.x]
            xdot = [s for p in model.particles for s in p.xdot]
            rows = maximal_rows(model, MaximalKinematics(model).point_substitution, x, xdot)
            reduced = Kinematics(model).point_substitution
            expected = {c.name: c.expr.xreplace(reduced)
                        for c in [*model.holonomic_constraints, *model.velocity_constraints]}
            # one random state: a wrong row differs at almost every state
            reduced_values, values = _on_parameterization(model, rng)

            def close(label, got, want):
                got, want = _value(got, values), _value(want, reduced_values)
                self.assertAlmostEqual(got, want, delta=1e-12 * (1 + abs(want)),
                                       msg=f"{name}: {label}")

            for row in rows.holonomic:
                if row.label.startswith("holonomic constraint"):
                    close(row.label, row.value, expected[row.label.split("'")[1]])
                else:  # a wheel's contact height: 0 where the reduced model has no row
                    wheel = row.label.split("'")[1]
                    close(row.label, row.value,
                          expected.get(f"{wheel}_contact", sp.Integer(0)))
            for row, axis in zip(rows.velocity, "xy" * len(model.wheels)):
                wheel = row.label.split("'")[1]
                value = row.bias + sum(a * v for a, v in zip(row.coefficients, xdot))
                close(row.label, value, expected[f"{wheel}_{axis}"])

    def test_contact_forces_act_along_the_heights_gradient_for_a_rigid_wheel(self):
        model = _load("rolling_disk")
        wheel = model.wheels[0]
        x = [s for p in model.particles for s in p.x]
        xdot = [s for p in model.particles for s in p.xdot]
        height = maximal_rows(model, {}, x, xdot).holonomic[0]
        rng = random.Random(5)
        _, values = _on_parameterization(model, rng)
        centre = sum((p.x for p in wheel.body.particles), sp.zeros(3, 1)) / 4
        omega = sp.Matrix([rng.uniform(-1, 1) for _ in range(3)])
        translation = sp.Matrix([rng.uniform(-1, 1) for _ in range(3)])
        rigid = {}
        for particle in wheel.body.particles:  # xdot of a rigid motion about the centre
            arm = (particle.x - centre).xreplace(values)
            rigid.update(zip(particle.xdot, translation + omega.cross(arm)))
        gradient_rate = sum(height.value.diff(s) * rigid[v] for s, v in zip(x, xdot))
        direction_rate = sum(g * rigid[v] for g, v in zip(height.direction, xdot))
        self.assertAlmostEqual(_value(gradient_rate, values), _value(direction_rate, values),
                               places=12)

    def test_penalty_forces_of_the_rows_are_in_the_maximal_model(self):
        model = _load("four_bar")
        plain = derive_maximal(model, symbolic_jacobians=False)
        self.assertEqual(plain.constraint_names[-2:], ["holonomic constraint 'loop_C_x'",
                                                       "holonomic constraint 'loop_C_y'"])
        inputs = {*plain.x, *plain.xdot, model.time, *(p.symbol for p in model.parameters)}
        for force in plain.total_forces:
            self.assertLessEqual(force.free_symbols - inputs,
                                 {sp.Symbol("kappa", positive=True),
                                  sp.Symbol("penalty_damping", nonnegative=True)})


class NoMaximalFormTest(unittest.TestCase):

    def _model(self, text: str, path):
        path.write_text(text, encoding="utf-8")
        return load_model(str(path), None)[0]

    def test_a_row_in_the_coordinates_is_named_with_its_line(self):
        with tempfile.TemporaryDirectory() as folder:
            model = self._model(
                "from gencoord import Model\n"
                "model = Model(dim=2)\n"
                "x = model.coordinate('x', 'x', initial=1.0)\n"
                "y = model.coordinate('y', 'y')\n"
                "model.particle('bob', mass=1.0, position=[x, y])\n"
                "model.holonomic_constraint(x**2 + y**2 - 1, name='rod')\n",
                Path(folder) / "circle.py")
        self.assertFalse(has_maximal_model(model))
        self.assertIn("holonomic constraint 'rod' (line 6) is written in the coordinates",
                      maximal_constraint_problem(model))

    def test_a_flat_wheel_is_named(self):
        with tempfile.TemporaryDirectory() as folder:
            text = (MODELS / "rolling_disk.py").read_text(encoding="utf-8")
            model = self._model(text.replace('h = model.parameter("h", 0.02',
                                             'h = model.parameter("h", 0.0'),
                                Path(folder) / "coin.py")
        self.assertFalse(has_maximal_model(model))
        self.assertIn("wheel 'rolling'", maximal_constraint_problem(model))
        self.assertIn("give the wheel some thickness", maximal_constraint_problem(model))


if __name__ == "__main__":
    unittest.main()
