# SPDX-License-Identifier: BSD-3-Clause
"""The checks of a tree of particles read its joints, not the flat J.

Kinematics.numeric_jacobian assembles a tree's J from each joint's S_i = d offset_i / d q_i
(a particle's rows are its parent's plus its own joint's columns); the rank check and the
singularity analysis sample it. This checks the assembled J against SymPy's Jacobian of the
stacked positions, the sums that spare SymPy's matrix arithmetic (sums.py) against SymPy's,
and that the conditioning sampling of a model too large for it says so.
"""

from __future__ import annotations

import math
import random
import unittest
from unittest import mock

import sympy as sp

from gencoord.checks import singularities
from gencoord.derive.dense import Kinematics
from gencoord.generate.load import load_model
from gencoord.symbolic.sums import difference, dot

from .test_recursive import SIX_LINKS, particle_trees


class TreeJacobianTest(unittest.TestCase):

    def test_assembled_jacobian_equals_sympys(self):
        rng = random.Random(3)
        for name, model, _ in particle_trees():
            with self.subTest(name):
                kin = Kinematics(model)
                self.assertIsNotNone(kin.tree)
                q = [c.symbol for c in model.coordinates]
                stacked = sp.Matrix.vstack(*[p.position for p in model.particles])
                reference = sp.lambdify([q, model.time],
                                        stacked.jacobian(q).xreplace(kin.defaults).tolist(),
                                        "math")
                evaluate = kin.numeric_jacobian()
                for _ in range(3):
                    values = [rng.uniform(-math.pi, math.pi) for _ in q]
                    t = rng.uniform(0.0, 10.0)
                    for row, expected_row in zip(evaluate(values, t), reference(values, t),
                                                 strict=True):
                        for value, want in zip(row, expected_row):
                            self.assertAlmostEqual(value, float(want), delta=1e-12)

    def test_joint_jacobians_have_one_column_per_introduced_coordinate(self):
        model, _, _ = load_model(str(SIX_LINKS[0]), SIX_LINKS[1])
        kin = Kinematics(model)
        joints = kin.numeric_joint_jacobians()([0.1] * len(model.coordinates), 0.0)
        self.assertEqual([(len(s), len(s[0])) for s in joints],
                         [(model.dim, len(node.coordinates)) for node in kin.tree.nodes])


class SumsTest(unittest.TestCase):

    def test_difference_of_a_sum_that_extends_another(self):
        a, b, c, t = sp.symbols("a b c t")
        base = sp.Matrix([sp.sin(a) + sp.cos(b) + 1, t * a])
        x = sp.Matrix([sp.sin(a) + sp.cos(b) + 1 + sp.sin(c), t * a - sp.cos(c)])
        self.assertEqual(difference(x, base), x - base)
        self.assertEqual(difference(x, base), sp.Matrix([sp.sin(c), -sp.cos(c)]))

    def test_difference_where_terms_merged_falls_back_to_subtraction(self):
        a, b = sp.symbols("a b")
        base = sp.Matrix([sp.sin(a) + 1])
        x = sp.Matrix([2 * sp.sin(a) + 3 + b])  # like terms and numbers combined
        self.assertEqual(difference(x, base), sp.Matrix([sp.sin(a) + 2 + b]))

    def test_dot_equals_sympys(self):
        u = sp.Matrix(sp.symbols("u0:3"))
        w = sp.Matrix([sp.sin(u[0]), u[1] / sp.sqrt(u[2]**2 + 1), 3])
        self.assertEqual(dot(u, w), u.dot(w))


class ConditioningLimitTest(unittest.TestCase):

    def test_a_model_beyond_the_limit_is_not_sampled_and_says_so(self):
        model, _, _ = load_model(str(SIX_LINKS[0]), SIX_LINKS[1])
        with mock.patch.object(singularities, "CONDITIONING_MAX_NQ", 3):
            report = singularities.analyse_singularities(model)
        self.assertEqual(report.worst_configuration, "")
        self.assertTrue(any("Conditioning of J not sampled" in note and "nq = 3" in note
                            for note in report.notes), report.notes)


if __name__ == "__main__":
    unittest.main()
