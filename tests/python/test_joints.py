# SPDX-License-Identifier: BSD-3-Clause
"""Joint trees without a URDF: frames composed in URDF's conventions, bodies at their centre of
mass, massless links, joint damping, and maximal-model pins whose two points coincide at
every configuration."""

from __future__ import annotations

import math
import random
import unittest

import sympy as sp

from gencoord import (Continuous, Fixed, Model, ModelError, Origin, Prismatic, Revolute,
                      add_free_base, add_link)
from gencoord.checks.atlas import check_atlas
from gencoord.dsl.items import Point

INERTIA = [[0.02, 0.001, 0], [0.001, 0.03, -0.002], [0, -0.002, 0.025]]


def evaluate(model: Model, expressions, q_values: list[float]) -> list[float]:
    """The expressions' values at q (in declaration order), through lambdify."""
    symbols = [c.symbol for c in model.coordinates]
    function = sp.lambdify(symbols, [sp.sympify(e) for e in expressions], "math")
    return [float(v) for v in function(*q_values)]


def random_q(model: Model, rng: random.Random) -> list[float]:
    return [rng.uniform(-math.pi, math.pi) for _ in model.coordinates]


def pin_gaps(model: Model, q_values: list[float]) -> list[float]:
    """|point - anchor| of every pin at q."""
    gaps = []
    for pin in (c for c in model.constraints if type(c).__name__ == "Pin"):
        anchor = pin.anchor.position if isinstance(pin.anchor, Point) else pin.anchor
        difference = evaluate(model, list(pin.particle.position - anchor), q_values)
        gaps.append(math.sqrt(sum(d * d for d in difference)))
    return gaps


def pins_of(model: Model) -> list[str]:
    return [c.name for c in model.constraints if type(c).__name__ == "Pin"]


class FrameCompositionTest(unittest.TestCase):

    def test_revolute_prismatic_fixed(self):
        model = Model(dim=3)
        first = add_link(model, "first", None, Revolute(
            [0, 0, 1], Origin(xyz=[0, 0, 0.5], rpy=[0, 0, math.pi / 2]), name="yaw"))
        second = add_link(model, "second", first, Prismatic(
            [1, 0, 0], Origin(xyz=[0.2, 0, 0], rpy=[math.pi / 2, 0, 0]), name="slide"))
        tool = add_link(model, "tool", second, Fixed(Origin(xyz=[0, 0, 0.1])))
        yaw, slide = first.coordinate, second.coordinate
        self.assertEqual([c.name for c in model.coordinates], ["yaw", "slide"])
        self.assertIsNone(tool.coordinate)
        # by hand: Rz(pi/2 + yaw) about (0, 0, 0.5), then x' = (0.2 + slide) along the
        # turned x axis, then Rx(pi/2); the tool 0.1 along that frame's z
        for a, s in ((0.3, 0.1), (-1.2, -0.4)):
            c, d = math.cos(math.pi / 2 + a), math.sin(math.pi / 2 + a)
            origin = [(0.2 + s) * c, (0.2 + s) * d, 0.5]
            z_axis = [d, -c, 0]  # Rz(pi/2 + a) Rx(pi/2) e_z = Rz(.) (-e_y)
            got = evaluate(model, list(tool.frame.origin), [a, s])
            want = [o + 0.1 * z for o, z in zip(origin, z_axis)]
            for g, w in zip(got, want):
                self.assertAlmostEqual(g, w, places=12)
            got = evaluate(model, list(second.frame.rotation[:, 2]), [a, s])
            for g, w in zip(got, z_axis):
                self.assertAlmostEqual(g, w, places=12)
        self.assertEqual(second.frame.rotation.free_symbols, {yaw})
        self.assertIn(slide, second.frame.origin.free_symbols)

    def test_oblique_axis_and_origin_rotation(self):
        model = Model(dim=3)
        link = add_link(model, "link", None, Continuous(
            [1, 2, 2], Origin(rpy=[0.1, -0.4, 0.25]), name="q"))
        R0 = [[float(v) for v in row] for row in sp.Matrix(
            sp.rot_axis3(-0.25) * sp.rot_axis2(0.4) * sp.rot_axis1(-0.1)).tolist()]
        for angle in (0.7, -2.1):
            u = [1 / 3, 2 / 3, 2 / 3]
            K = [[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]]
            K2 = [[sum(K[i][k] * K[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
            turn = [[(i == j) + math.sin(angle) * K[i][j] + (1 - math.cos(angle)) * K2[i][j]
                     for j in range(3)] for i in range(3)]
            want = [sum(R0[i][k] * turn[k][j] for k in range(3))
                    for i in range(3) for j in range(3)]
            for g, w in zip(evaluate(model, list(link.frame.rotation), [angle]), want):
                self.assertAlmostEqual(g, w, places=12)

    def test_right_angles_are_exact(self):
        origin = Origin(rpy=[math.pi / 2, 0, 3.141592653589793])
        self.assertEqual(origin.rpy, (sp.pi / 2, 0, sp.pi))
        self.assertEqual(origin.frame().rotation, sp.Matrix([[-1, 0, 0], [0, 0, 1], [0, 1, 0]]))
        self.assertNotEqual(Origin(rpy=[1.5708, 0, 0]).rpy[0], sp.pi / 2)


class BodiesAndPinsTest(unittest.TestCase):

    def test_chain_pins_coincide(self):
        model = Model(dim=3)
        upper = add_link(model, "upper", None, Revolute(
            [0, 1, 0], Origin(xyz=[0, 0, 1], rpy=[0.2, 0, 0.3]), name="shoulder"),
            mass=2.0, inertia=INERTIA, com=Origin(xyz=[0.1, 0, -0.2], rpy=[0.3, 0.1, 0]))
        lower = add_link(model, "lower", upper, Revolute(
            [1, 1, 0], Origin(xyz=[0, 0.05, -0.4], rpy=[0, 0.5, 0]), name="elbow"),
            mass=1.0, inertia=INERTIA, com=Origin(xyz=[0, 0, -0.15]))
        hand = add_link(model, "hand", lower, Fixed(Origin(xyz=[0.02, 0, -0.3],
                                                           rpy=[0.4, 0.2, -0.1]), name="wrist"),
                        mass=0.5, inertia=INERTIA, com=Origin(xyz=[0, 0.01, -0.05]))
        self.assertEqual([b.name for b in model.bodies], ["upper", "lower", "hand"])
        self.assertEqual(pins_of(model), ["shoulder_a", "shoulder_b", "elbow_a", "elbow_b",
                                          "wrist_a", "wrist_b", "wrist_c"])
        # a pin of the shoulder goes to a world position, the others join two bodies
        pins = [c for c in model.constraints if type(c).__name__ == "Pin"]
        self.assertNotIsInstance(pins[0].anchor, Point)
        self.assertIs(pins[2].anchor.body, upper.body)
        self.assertIs(pins[2].particle.body, lower.body)
        self.assertIs(pins[4].anchor.body, lower.body)
        rng = random.Random(3)
        for _ in range(5):
            for gap in pin_gaps(model, random_q(model, rng)):
                self.assertLess(gap, 1e-12)
        # the body's frame is the link's times com
        q = random_q(model, rng)
        centre = evaluate(model, list(hand.body.frame.origin), q)
        want = evaluate(model, list(hand.frame.point([0, 0.01, -0.05])), q)
        for g, w in zip(centre, want):
            self.assertAlmostEqual(g, w, places=12)

    def test_massless_links_pin_to_the_nearest_massive_ancestor(self):
        model = Model(dim=3)
        arm = add_link(model, "arm", None, Revolute([0, 0, 1], Origin(xyz=[0, 0, 0.3])),
                       mass=1.0, inertia=INERTIA)
        flange = add_link(model, "flange", arm, Fixed(Origin(xyz=[0.4, 0, 0],
                                                             rpy=[0, math.pi / 2, 0])))
        adapter = add_link(model, "adapter", flange, Fixed(Origin(xyz=[0, 0.1, 0])))
        add_link(model, "finger", adapter, Revolute([0, 1, 0], Origin(
            xyz=[0, 0, 0.05])), mass=0.2, inertia=INERTIA, com=Origin(xyz=[0, 0, 0.03]))
        self.assertIsNone(flange.body)
        self.assertIsNone(adapter.body)
        self.assertIs(adapter.support[0], arm.body)
        finger_pins = [c for c in model.constraints
                       if type(c).__name__ == "Pin" and c.name.startswith("finger")]
        self.assertEqual(len(finger_pins), 2)
        self.assertTrue(all(p.anchor.body is arm.body for p in finger_pins))
        rng = random.Random(5)
        for _ in range(5):
            for gap in pin_gaps(model, random_q(model, rng)):
                self.assertLess(gap, 1e-12)

    def test_massless_moving_link_leaves_the_joint_unpinned(self):
        model = Model(dim=3)
        gimbal = add_link(model, "gimbal", None, Revolute([0, 0, 1], Origin()))
        body = add_link(model, "body", gimbal, Revolute([1, 0, 0], Origin()), mass=1.0,
                        inertia=INERTIA)
        self.assertIsNone(gimbal.support)
        self.assertIn("massless and moves", body.unpinned)
        self.assertEqual(pins_of(model), [])

    def test_prismatic_joint_has_no_pins(self):
        model = Model(dim=3)
        cart = add_link(model, "cart", None, Prismatic([1, 0, 0], Origin()), mass=1.0,
                        inertia=INERTIA)
        self.assertEqual(pins_of(model), [])
        self.assertIn("prismatic", cart.unpinned)
        self.assertEqual(cart.body.frame.origin.free_symbols, {cart.coordinate})

    def test_link_welded_to_the_world_has_no_body(self):
        model = Model(dim=3)
        base = add_link(model, "base", None, Fixed(Origin(xyz=[0, 0, 1])), mass=10.0,
                        inertia=INERTIA)
        arm = add_link(model, "arm", base, Revolute([0, 0, 1], Origin()), mass=1.0,
                       inertia=INERTIA)
        self.assertIsNone(base.body)
        self.assertEqual([b.name for b in model.bodies], ["arm"])
        self.assertEqual(evaluate(model, list(arm.frame.origin), [0.3]), [0, 0, 1])

    def test_damping_and_limits(self):
        from gencoord import Limits
        model = Model(dim=3)
        link = add_link(model, "link", None, Revolute([0, 0, 1], Origin(), Limits(0.2, 1.0, 5),
                                                      damping=0.3, name="hinge"),
                        mass=1.0, inertia=INERTIA)
        coordinate = model.coordinates[0]
        self.assertEqual(coordinate.initial, 0.2)
        self.assertIn("limits [0.2, 1], effort 5", coordinate.description)
        self.assertEqual(link.limits.upper, 1.0)
        self.assertEqual([f.force for f in model.generalized_forces],
                         [-0.3 * model.rate(link.coordinate)])

    def test_link_and_joint_may_share_a_name(self):
        model = Model(dim=3)
        add_link(model, "elbow", None, Revolute([0, 0, 1], Origin(), name="elbow"), mass=1.0,
                 inertia=INERTIA)
        self.assertEqual(model.coordinates[0].name, "elbow")
        self.assertEqual(model.bodies[0].name, "elbow_body")

    def test_refusals(self):
        model = Model(dim=3)
        with self.assertRaisesRegex(ModelError, "joint 'j'.*axis is zero"):
            add_link(model, "a", None, Revolute([0, 0, 0], Origin(), name="j"))
        with self.assertRaisesRegex(ModelError, "link 'a'.*both mass and inertia"):
            add_link(model, "a", None, Revolute([0, 0, 1], Origin()), mass=1.0)
        with self.assertRaisesRegex(ModelError, "link 'a'.*Revolute"):
            add_link(model, "a", None, "revolute")


class FreeBaseTest(unittest.TestCase):

    def chart(self, name: str, damping: float = 0.0) -> Model:
        model = Model(dim=3, chart=name)
        base = add_free_base(model, "base", 3.0, INERTIA, Origin(xyz=[0.1, 0, 0]), chart=name)
        add_link(model, "arm", base, Revolute([0, 1, 0], Origin(xyz=[0.3, 0, 0]),
                                              damping=damping, name="hinge"),
                 mass=1.0, inertia=INERTIA, com=Origin(xyz=[0, 0, -0.2]))
        return model

    def test_charts(self):
        zyx, yzx = self.chart("zyx"), self.chart("yzx")
        self.assertEqual([c.name for c in zyx.coordinates],
                         ["x", "y", "z", "yaw", "pitch", "roll", "hinge"])
        self.assertEqual([c.name for c in yzx.coordinates],
                         ["x", "y", "z", "heading", "attitude", "bank", "hinge"])
        zyx.add_chart(yzx)
        check_atlas(zyx)
        rng = random.Random(11)
        for _ in range(3):
            for gap in pin_gaps(zyx, random_q(zyx, rng)):
                self.assertLess(gap, 1e-12)

    def test_damping_in_a_chart_is_a_torque_pair(self):
        model = self.chart("zyx", damping=0.4)
        self.assertEqual(model.generalized_forces, [])
        self.assertEqual([t.name for t in model.torques], ["hinge_damping",
                                                           "hinge_damping_reaction"])
        # the torques' virtual work is -c qdot dq: Q = J_w^T tau on the hinge alone
        from gencoord.dsl.bodies import torque_generalized_forces
        q = [c.symbol for c in model.coordinates]
        forces = torque_generalized_forces(model, q)
        values = dict(zip(q, [0.1, -0.2, 0.3, 0.4, -0.5, 0.6, 0.7]))
        values[model.rate(q[-1])] = 1.3
        got = [float(force.xreplace(values)) for force in forces]
        want = [0.0] * (len(q) - 1) + [-0.4 * 1.3]
        for g, w in zip(got, want):
            self.assertAlmostEqual(g, w, places=12)


if __name__ == "__main__":
    unittest.main()
