# SPDX-License-Identifier: BSD-3-Clause
"""Free and ball joints: unit quaternions among the coordinates and generalized speeds (the
body twist, the angular velocity) with q' = G(q) v. What the model records, the header's
members, and every refusal with its item. The dynamics are checked against the dense
derivation in test_recursive.py and against MuJoCo in tests/robots."""

from __future__ import annotations

import unittest
from pathlib import Path

import sympy as sp

from gencoord import Ball, Free, Model, Origin, Revolute, add_link
from gencoord.checks.atlas import check_atlas
from gencoord.dsl.quaternions import quaternion_rate, quaternion_rotation
from gencoord.errors import ModelError
from gencoord.generate.stages import generate
from gencoord.options import GenerateOptions

QUATERNION_TREE = Path(__file__).parent / "tree_models" / "quaternion_tree.py"
INERTIA = [[0.02, 0, 0], [0, 0.03, 0], [0, 0, 0.04]]


def _free_body(dim: int = 3, chart: str | None = None) -> tuple[Model, object]:
    model = Model(dim=dim, chart=chart)
    body = add_link(model, "body", None, Free(Origin(xyz=[0, 0, 1])), mass=1.0, inertia=INERTIA)
    return model, body


class QuaternionTest(unittest.TestCase):

    def test_the_rate_turns_r_by_the_body_angular_velocity(self):
        # R^T R' = [omega]x exactly on the unit sphere: the rate's convention is the body's axes
        q = sp.symbols("w x y z", real=True)
        omega = sp.symbols("a b c", real=True)
        rotation = quaternion_rotation(q)
        rate = quaternion_rate(q, omega)
        spin = rotation.T * sum((rotation.diff(s) * d for s, d in zip(q, rate)), sp.zeros(3))
        unit = {q[0]: sp.Rational(1, 2), q[1]: sp.Rational(1, 2), q[2]: sp.Rational(-1, 2),
                q[3]: sp.Rational(1, 2)}
        self.assertEqual(spin.subs(unit).applyfunc(sp.expand),
                         sp.Matrix([[0, -omega[2], omega[1]], [omega[2], 0, -omega[0]],
                                    [-omega[1], omega[0], 0]]))


class FreeAndBallJointTest(unittest.TestCase):

    def test_coordinates_speeds_and_rates(self):
        model, body = _free_body()
        arm = add_link(model, "arm", body, Ball(Origin(xyz=[0, 0, -0.2])), mass=1.0,
                       inertia=INERTIA)
        self.assertEqual((model.nq, model.nv, model.quaternions), (11, 9, [3, 7]))
        self.assertEqual([s.name for s in model.speeds][:3], ["body_vx", "body_vy", "body_vz"])
        self.assertEqual(body.speeds, [s.symbol for s in model.speeds[:6]])
        self.assertEqual(arm.speeds, [s.symbol for s in model.speeds[6:]])
        rates = model.coordinate_rates()
        # the position's rate is R v: at the identity quaternion, v itself
        at_rest = {c.symbol: c.initial for c in model.coordinates}
        self.assertEqual([r.subs(at_rest) for r in rates[:3]], body.speeds[:3])
        self.assertEqual(model.on_manifold([0, 0, 0, 2, 0, 0, 0, 0, 0, 0, 0])[3:8],
                         [1.0, 0.0, 0.0, 0.0, 1.0])

    def test_the_header_has_the_kinematic_equation_and_the_maximal_model(self):
        header = generate(str(QUATERNION_TREE), options=GenerateOptions(maximal=True)).header
        for text in ("static constexpr int nq = 12;", "static constexpr int nv = 10;",
                     "quaternion_starts{{3, 7}}", "static QVector<Scalar> coordinate_rates(",
                     "static VMatrix<Scalar> mass_matrix(", "  struct Maximal {"):
            self.assertIn(text, header)
        self.assertNotIn("No struct Maximal", header)

    def test_refusals_name_the_item(self):
        model, _ = _free_body()
        qw = model.coordinates[3].symbol
        cases = [
            (lambda: model.rate(qw), "body_qw belongs to a free or ball joint"),
            (lambda: model.generalized_force(qw, 1.0), "body_qw belongs to a free or ball joint"),
            (lambda: model.joint_spring(qw, 1.0), "body_qw belongs to a free or ball joint"),
            (lambda: _free_body(dim=2), "a free joint needs a 3D model"),
        ]
        for make, message in cases:
            with self.subTest(message=message):
                with self.assertRaisesRegex(ModelError, message):
                    make()

    def test_an_atlas_of_quaternion_charts_is_refused(self):
        model, _ = _free_body(chart="a")
        other, _ = _free_body(chart="b")
        model.add_chart(other)
        with self.assertRaisesRegex(ModelError, "cannot have free or ball joints"):
            check_atlas(model)

    def test_a_revolute_joint_under_a_ball_keeps_its_rate_as_speed(self):
        model, body = _free_body()
        hinge = add_link(model, "hinge", body, Revolute([0, 1, 0]), mass=1.0, inertia=INERTIA)
        self.assertEqual(model.speeds[-1].symbol, model.rate(hinge.coordinate))
        self.assertEqual(model.coordinate_rates()[-1], model.rate(hinge.coordinate))


if __name__ == "__main__":
    unittest.main()
