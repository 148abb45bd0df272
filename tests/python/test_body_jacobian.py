# SPDX-License-Identifier: BSD-3-Clause
"""The numeric J of a joint tree of bodies (gencoord/derive/body_jacobian.py), which the
sampled checks use, against the compiled symbolic J at random configurations: a fixed-base
arm, a quadruped and a floating base in both Euler charts."""

from __future__ import annotations

import random
import unittest
from pathlib import Path

from gencoord.derive.body_jacobian import numeric_body_jacobian
from gencoord.derive.body_tree import body_tree
from gencoord.derive.dense import Kinematics
from gencoord.generate.load import load_model

REPOSITORY = Path(__file__).resolve().parents[2]
ROBOTS = [REPOSITORY / "models" / "iiwa14.urdf", REPOSITORY / "models" / "quadruped.urdf",
          REPOSITORY / "tests" / "robots" / "floating_leg.py",
          REPOSITORY / "tests" / "robots" / "floating_leg_yzx.py"]


class BodyJacobianTest(unittest.TestCase):

    def test_equals_the_symbolic_jacobian(self):
        rng = random.Random(7)
        for path in ROBOTS:
            with self.subTest(robot=path.name):
                model, _, _ = load_model(str(path), {}, None, None)
                kin = Kinematics(model)
                tree = body_tree(model)
                self.assertIsNotNone(tree)
                from_joints = numeric_body_jacobian(tree, kin.q, kin.t, kin.defaults,
                                                    kin.particles)
                symbolic = kin._flat_numeric_jacobian()
                for _ in range(20):
                    q = [rng.uniform(-3.0, 3.0) for _ in kin.q]
                    a, b = from_joints(q, 0.25), symbolic(q, 0.25)
                    self.assertEqual((len(a), len(a[0])), (len(b), len(b[0])))
                    scale = max(abs(x) for row in b for x in row)
                    for row_a, row_b in zip(a, b):
                        for x, y in zip(row_a, row_b):
                            self.assertAlmostEqual(x, y, delta=1e-12 * scale)

    def test_the_kinematics_use_it_for_a_joint_tree(self):
        model, _, _ = load_model(str(ROBOTS[0]), {}, None, None)
        kin = Kinematics(model)
        jacobian = kin.numeric_jacobian()
        self.assertEqual(jacobian.__module__, "gencoord.derive.body_jacobian")
        self.assertEqual(len(jacobian([0.1] * len(kin.q), 0.0)), 3 * len(kin.particles))


if __name__ == "__main__":
    unittest.main()
