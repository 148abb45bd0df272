# SPDX-License-Identifier: BSD-3-Clause
"""The maximal model's forces: plain expressions by default, named intermediates on request.

`derive_maximal` gives the model tests' reference values expressions of x, xdot, t and the
parameters; the pipeline asks large models for each constraint's penalty force as a named
intermediate, which must change neither the values nor the Jacobians' sparsity pattern.
"""

from __future__ import annotations

import random
import unittest

import sympy as sp

from gencoord.generate.load import load_model
from gencoord.derive.maximal import KAPPA, PENALTY_DAMPING, derive_maximal

from .support import MODELS


class MaximalForcesTest(unittest.TestCase):

    def setUp(self):
        self.model, _, _ = load_model(str(MODELS / "compound_pendulum.py"), None)

    def test_plain_by_default(self):
        plain = derive_maximal(self.model, symbolic_jacobians=False)
        self.assertEqual(plain.definitions, [])
        inputs = {*plain.x, *plain.xdot, self.model.time, KAPPA, PENALTY_DAMPING,
                  *(p.symbol for p in self.model.parameters)}
        for force in plain.total_forces:
            self.assertLessEqual(force.free_symbols, inputs)

    def test_named_forces_have_the_same_values_and_pattern(self):
        plain = derive_maximal(self.model, symbolic_jacobians=False)
        named = derive_maximal(self.model, symbolic_jacobians=False, named=True)
        self.assertTrue(named.definitions)
        self.assertEqual(named.force_jacobian_x, plain.force_jacobian_x)
        self.assertEqual(named.force_jacobian_xdot, plain.force_jacobian_xdot)
        rng = random.Random(3)
        point = {s: sp.Float(rng.uniform(-1, 1)) for s in [*plain.x, *plain.xdot]}
        point.update({self.model.time: sp.Float(0.4), KAPPA: sp.Float(1e3),
                      PENALTY_DAMPING: sp.Float(0.5)})
        point.update({p.symbol: sp.Float(p.default) for p in self.model.parameters})
        for symbol, expr in named.definitions:
            point[symbol] = expr.xreplace(point)
        for a, b in zip(named.total_forces, plain.total_forces):
            self.assertAlmostEqual(float(a.xreplace(point)), float(b.xreplace(point)), places=9)

    def test_named_forces_are_not_differentiated_symbolically(self):
        with self.assertRaises(ValueError):
            derive_maximal(self.model, symbolic_jacobians=True, named=True)


if __name__ == "__main__":
    unittest.main()
