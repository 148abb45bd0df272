# SPDX-License-Identifier: BSD-3-Clause
"""Joint friction: URDF <dynamics friction> and the joints' `friction` argument give the
smoothed Coulomb friction -F tanh(qdot / s), s the model's parameter joint_friction_speed. A
slider coasting to rest follows the closed form of m v' = -F tanh(v / s); a mimic joint's
friction acts through its multiplier; an atlas gets it as a torque pair; negative values are
refused in one line."""

from __future__ import annotations

import math
import shutil
import tempfile
import unittest
from pathlib import Path

import sympy as sp

from gencoord import Model, ModelError, Origin, Prismatic, Revolute, add_link
from gencoord.derive.dense import derive
from gencoord.dsl.joints import FRICTION_SPEED
from gencoord.generate.load import load_model

from .support import describe, run_generate

INERTIA = [[0.02, 0, 0], [0, 0.03, 0], [0, 0, 0.025]]


def urdf(joints: str, links: tuple[str, ...] = ("base", "arm", "hand")) -> str:
    inertial = ('<inertial><mass value="1.5"/><inertia ixx="0.02" iyy="0.03" izz="0.025"/>'
                '</inertial>')
    bodies = "\n".join(f'<link name="{name}">{inertial}</link>' for name in links)
    return f'<robot name="r">\n{bodies}\n{joints}\n</robot>\n'


def joint(name: str, parent: str, child: str, kind: str = "revolute", extra: str = "") -> str:
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/>'
            f'<child link="{child}"/><axis xyz="0 0 1"/>'
            f'<limit lower="-1" upper="1" effort="5" velocity="2"/>{extra}</joint>')


def forces_on(model: Model, name: str) -> list[sp.Expr]:
    return [f.force for f in model.generalized_forces if f.name == name]


class UrdfFrictionTest(unittest.TestCase):

    def setUp(self):
        self.folder = Path(tempfile.mkdtemp())
        self.addCleanup(shutil.rmtree, self.folder, ignore_errors=True)

    def load(self, text: str) -> Model:
        path = self.folder / "robot.urdf"
        path.write_text(text, encoding="utf-8")
        return load_model(str(path))[0]

    def test_friction_is_a_smoothed_coulomb_law_with_one_speed_parameter(self):
        model = self.load(urdf(
            joint("shoulder", "base", "arm", extra='<dynamics damping="0.2" friction="0.7"/>')
            + joint("elbow", "arm", "hand", extra='<dynamics friction="0.3"/>')))
        speeds = [p for p in model.parameters if p.name == "joint_friction_speed"]
        self.assertEqual(len(speeds), 1, "one smoothing speed for every joint")
        self.assertEqual(speeds[0].default, FRICTION_SPEED)
        s = speeds[0].symbol
        shoulder, elbow = (c.symbol for c in model.coordinates)
        self.assertEqual(forces_on(model, "shoulder_friction"),
                         [-0.7 * sp.tanh(model.rate(shoulder) / s)])
        self.assertEqual(forces_on(model, "elbow_friction"),
                         [-0.3 * sp.tanh(model.rate(elbow) / s)])
        self.assertEqual(forces_on(model, "shoulder_damping"), [-0.2 * model.rate(shoulder)])
        self.assertFalse(any("friction" in line for line in model.ignored), model.ignored)

    def test_no_friction_declares_no_parameter(self):
        model = self.load(urdf(joint("shoulder", "base", "arm",
                                     extra='<dynamics damping="0.2" friction="0"/>'),
                               links=("base", "arm")))
        self.assertNotIn("joint_friction_speed", [p.name for p in model.parameters])

    def test_a_mimic_joint_rubs_through_its_multiplier(self):
        model = self.load(urdf(
            joint("shoulder", "base", "arm")
            + joint("finger", "arm", "hand", kind="prismatic",
                    extra='<mimic joint="shoulder" multiplier="-2" offset="0.1"/>'
                          '<dynamics friction="0.5"/>')))
        (shoulder,) = (c.symbol for c in model.coordinates)
        s = next(p.symbol for p in model.parameters if p.name == "joint_friction_speed")
        # its rate is -2 qdot and its virtual displacement -2 dq: -2 (-0.5 tanh(-2 qdot / s))
        (force,) = forces_on(model, "finger_friction")
        self.assertEqual(sp.simplify(force - sp.tanh(-2 * model.rate(shoulder) / s)), 0)

    def test_dynamics_of_fixed_and_floating_joints_is_listed_as_not_read(self):
        model = self.load(urdf(joint("shoulder", "base", "arm")
                               + joint("weld", "arm", "hand", kind="fixed",
                                       extra='<dynamics friction="0.4"/>')))
        self.assertEqual(model.ignored, ["<dynamics> of 1 fixed or floating joint(s) (weld): "
                                         "such a joint has no coordinate to damp"])

    def test_negative_friction_is_refused_in_one_line(self):
        path = self.folder / "negative.urdf"
        path.write_text(urdf(joint("shoulder", "base", "arm",
                                   extra='\n<dynamics friction="-0.1"/>'),
                             links=("base", "arm")), encoding="utf-8")
        result = run_generate(str(path), "-o", str(self.folder / "out"))
        self.assertEqual(result.returncode, 1, describe(result))
        self.assertRegex(result.stderr, r"negative\.urdf:\d+: error: joint 'shoulder': the "
                                        r"friction is -0\.1; give a non-negative friction")
        self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)
        self.assertFalse((self.folder / "out").exists(), "nothing half-written")

    def test_a_friction_header_generates(self):
        path = self.folder / "rubbing.urdf"
        path.write_text(urdf(joint("shoulder", "base", "arm", extra='<dynamics friction="0.7"/>'),
                             links=("base", "arm")), encoding="utf-8")
        result = run_generate(str(path), "-o", str(self.folder / "out"), "--quiet")
        self.assertEqual(result.returncode, 0, describe(result))
        header = (self.folder / "out" / "rubbing.hpp").read_text(encoding="utf-8")
        self.assertIn("double joint_friction_speed = 0.1;", header)
        self.assertIn("tanh(", header)


class DslFrictionTest(unittest.TestCase):

    def test_a_coasting_slider_follows_the_closed_form(self):
        """m v' = -F tanh(v / s) has sinh(v / s) = sinh(v0 / s) exp(-F t / (m s)): the
        generated equations of motion, integrated by RK4, follow it to 1e-9."""
        m, F, v0 = 2.0, 3.0, 1.5
        model = Model(dim=3)
        add_link(model, "slider", None, Prismatic([1, 0, 0], friction=F, name="rail"),
                 mass=m, inertia=INERTIA)
        model.gravity([0, 0, -9.81])
        d = derive(model)
        (s_symbol,) = [p.symbol for p in model.parameters if p.name == "joint_friction_speed"]
        s = FRICTION_SPEED
        qddot = (d.applied_forces[0] + d.inertial_forces[0]) / d.mass_matrix[0, 0]
        self.assertEqual(qddot.free_symbols, {d.v[0], s_symbol})
        acceleration = sp.lambdify([d.v[0], s_symbol], qddot, "math")

        def acceleration_at(v: float) -> float:
            return acceleration(v, s)

        h, v, t = 1e-3, v0, 0.0
        worst = 0.0
        while t < 2.0:
            k1 = acceleration_at(v)
            k2 = acceleration_at(v + h / 2 * k1)
            k3 = acceleration_at(v + h / 2 * k2)
            k4 = acceleration_at(v + h * k3)
            v, t = v + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4), t + h
            exact = s * math.asinh(math.sinh(v0 / s) * math.exp(-F * t / (m * s)))
            worst = max(worst, abs(v - exact))
        self.assertLess(worst, 1e-9)
        # about Coulomb's stopping time m v0 / F = 1 s, the speed is a few s at most, then 0
        self.assertLess(v, 1e-3)

    def test_an_atlas_gets_a_torque_pair(self):
        model = Model(dim=3, chart="zyx")
        base = add_link(model, "base", None, Revolute([0, 0, 1], name="turn"), mass=1.0,
                        inertia=INERTIA)
        add_link(model, "arm", base, Revolute([0, 1, 0], Origin(xyz=[0, 0, 0.3]), friction=0.2,
                                              name="hinge"), mass=1.0, inertia=INERTIA)
        self.assertEqual([t.name for t in model.torques],
                         ["hinge_friction", "hinge_friction_reaction"])

    def test_negative_friction_is_refused(self):
        model = Model(dim=3)
        with self.assertRaisesRegex(ModelError, "the friction is -1; give a non-negative "
                                                "friction"):
            add_link(model, "slider", None, Prismatic([1, 0, 0], friction=-1, name="rail"),
                     mass=1.0, inertia=INERTIA)


if __name__ == "__main__":
    unittest.main()
