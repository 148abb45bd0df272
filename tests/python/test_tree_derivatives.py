# SPDX-License-Identifier: BSD-3-Clause
"""The closed-form residual Jacobians of revolute and prismatic trees (tree_derivatives.py)
against central differences of Newton-Euler's residual, in extended precision.

The differences use the recursion's own residual (body_recursion.py), which test_recursive
checks against the dense derivation; a step of 1e-12 in 40 digits leaves a truncation error
near 1e-24. A URDF's numbers are binary floats, which the two programs round differently near
1e-17, so they are held to 1e-12; a wrong term shows at O(1). The C++ model tests check the
generated kernels against central differences in double and against the 40-digit reference
values.
"""

from __future__ import annotations

import random
import unittest
from pathlib import Path

import mpmath
import sympy as sp

from gencoord.derive.body_kinematics import LinkKinematics
from gencoord.derive.body_recursion import body_recursive_dynamics
from gencoord.derive.body_tree import body_tree
from gencoord.derive.dense import Kinematics
from gencoord.derive.structured import Intermediates
from gencoord.derive.tree_derivatives import analytic_residual_jacobians
from gencoord.generate.load import load_model

from .support import relative_error

BRANCHED_ARM = Path(__file__).parent / "tree_models" / "branched_arm.urdf"
FORCED_ARM = Path(__file__).parent / "tree_models" / "forced_arm.py"
MOVING_PIVOT = Path(__file__).parent / "tree_models" / "moving_pivot.py"
DIGITS = 40
STEP = mpmath.mpf("1e-12")


def _load(path: Path):
    model, _, _ = load_model(str(path))
    return model, Kinematics(model)


def _closed_form(model, kin, min_mean_subtree=None):
    """(dr/dq, dr/dv, their definitions) from a LinkKinematics of its own."""
    names = Intermediates(prefix="__d")
    links = LinkKinematics(model, kin, body_tree(model), names)
    qdd = [speed.acceleration for speed in model.speeds]
    options = {} if min_mean_subtree is None else {"min_mean_subtree": min_mean_subtree}
    jacobians = analytic_residual_jacobians(model, links, kin.q, kin.v, qdd, **options)
    return jacobians, names.definitions


def _evaluator(definitions, outputs: list[sp.Expr]):
    """outputs(point) in DIGITS digits: the definitions they read, evaluated in order."""
    named = {s for s, _ in definitions}
    needed = set().union(*(e.free_symbols for e in outputs)) & named
    for symbol, expr in reversed(definitions):
        if symbol in needed:
            needed |= expr.free_symbols & named
    program = [(s, e) for s, e in definitions if s in needed]

    def values(point: dict) -> list:
        known = dict(point)
        for symbol, expr in program:
            known[symbol] = expr.xreplace(known).evalf(DIGITS)
        return [mpmath.mpf(sp.sympify(e).xreplace(known).evalf(DIGITS)) for e in outputs]
    return values


class ClosedFormJacobiansTest(unittest.TestCase):

    def test_equal_central_differences_of_the_residual(self):
        # revolute, continuous and prismatic joints, a weld carrying a body, a branch, joint
        # damping and friction (its subtrees are too short for the closed form to pay, so it is
        # asked for); the arms' generated kernels are checked in C++ (tests/robots/
        # derivatives_test.cc, tests/models/looped_kernels_test.cc)
        model, kin = _load(BRANCHED_ARM)
        (dr_dq, dr_dv), definitions = _closed_form(model, kin, 0.0)
        recursive = body_recursive_dynamics(model, kin, body_tree(model), derivation=False)
        residual = _evaluator(recursive.definitions, list(recursive.residual))
        jacobians = _evaluator(definitions, [*dr_dq, *dr_dv])
        rng = random.Random(BRANCHED_ARM.name)
        inputs = [*kin.q, *kin.v, *(s.acceleration for s in model.speeds)]
        with mpmath.workdps(DIGITS):
            point = {s: sp.Float(rng.uniform(-1.5, 1.5), DIGITS) for s in inputs}
            point.update({p.symbol: sp.Float(p.default * rng.uniform(0.8, 1.2), DIGITS)
                          for p in model.parameters})
            point[kin.t] = sp.Float(0.3, DIGITS)
            columns = []
            for w in [*kin.q, *kin.v]:
                ahead, behind = dict(point), dict(point)
                ahead[w] = point[w] + STEP
                behind[w] = point[w] - STEP
                columns.append([(a - b) / (2 * STEP) for a, b
                                in zip(residual(ahead), residual(behind))])
            n = len(kin.q)
            expected = [columns[j][i] for i in range(model.nv) for j in range(n)]
            expected += [columns[n + j][i] for i in range(model.nv) for j in range(model.nv)]
            self.assertLess(relative_error(jacobians(point), expected), 1e-12)

    def test_refused_whatever_the_subtrees(self):
        # external wrenches (springs, dampers, torques on bodies), a joint frame moving in time;
        # which trees of models/ get the closed form, test_recursive checks
        for path in (FORCED_ARM, MOVING_PIVOT):
            model, kin = _load(path)
            self.assertIsNone(_closed_form(model, kin, 0.0)[0], path.name)


if __name__ == "__main__":
    unittest.main()
