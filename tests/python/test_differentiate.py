# SPDX-License-Identifier: BSD-3-Clause
"""Forward-mode Jacobians through straight-line code (gencoord/derive/differentiate.py).

The derivatives are checked against SymPy's `diff` of the flattened outputs at random points,
including the cases the chain-rule sums handle specially: a derivative that is a number,
two intermediates passing on the same derivative (their terms merge and may cancel), and
a derivative of sin or cos that reads the intermediate already holding cos or sin.
"""

from __future__ import annotations

import random
import unittest

import sympy as sp

from gencoord.cxx.printer import ScalarCxxPrinter
from gencoord.derive.differentiate import (ChainSum, directional_derivatives,
                                           forward_derivatives, free_symbols_of)
from gencoord.optimize.opcount import count_ops

from .support import DIGITS

x, y, p = sp.symbols("x y p")
t = sp.symbols("t0:10")
PROGRAM = [
    (t[0], sp.sin(x)),
    (t[1], sp.cos(x)),
    (t[2], p * t[0] + y**2),
    (t[3], t[2] * t[1] - t[0]),
    (t[4], x + p),           # d/dx is the number 1
    (t[5], x * y - p),
    (t[6], t[2] + 1),        # passes d t2 on unchanged: same derivative symbol as t2
    (t[7], sp.exp(t[3])),    # beyond the own rules: SymPy's diff
]
OUTPUTS = [t[3] * t[4], t[6] - t[2], t[7] + t[5] * t[3], t[4] * t[5]]


def _value(expr):
    return expr.as_expr() if isinstance(expr, ChainSum) else expr


def _flattened(expr, program):
    for symbol, definition in reversed(program):
        expr = expr.subs(symbol, definition)
    return expr


class ForwardDerivativesTest(unittest.TestCase):

    def setUp(self):
        self.definitions, self.jacobian = forward_derivatives(
            PROGRAM, OUTPUTS, [x, y], sp.numbered_symbols("d"))

    def test_jacobian_matches_diff_of_the_flattened_outputs(self):
        rng = random.Random(7)
        for _ in range(3):
            point = {s: sp.Float(rng.uniform(-2, 2), DIGITS) for s in (x, y, p)}
            values = dict(point)
            for symbol, expr in PROGRAM + self.definitions:
                values[symbol] = _value(expr).xreplace(values).evalf(DIGITS)
            for i, output in enumerate(OUTPUTS):
                for j, variable in enumerate((x, y)):
                    expected = sp.diff(_flattened(output, PROGRAM), variable).xreplace(
                        point).evalf(DIGITS)
                    actual = _value(self.jacobian[i][j]).xreplace(values).evalf(DIGITS)
                    self.assertLess(abs(actual - expected), 1e-20 * (1 + abs(expected)),
                                    f"d output {i} / d {variable}")

    def test_merged_terms_cancel_to_an_exact_zero(self):
        # t6 - t2 = 1 whatever x and y are: both pass on the same derivative symbol
        self.assertEqual(self.jacobian[1], [0, 0])

    def test_derivative_of_sin_reads_the_cosine_intermediate(self):
        # d t0 / dx is t1, so no derivative calls cos or sin again
        for _, expr in self.definitions:
            self.assertFalse(_value(expr).has(sp.sin, sp.cos), expr)
        used = set().union(*(_value(e).free_symbols for _, e in self.definitions))
        self.assertIn(t[1], used)
        self.assertIn(t[0], used)  # d t1 / dx = -t0


class DirectionalDerivativesTest(unittest.TestCase):
    """One pass along a direction (dx, dy) equals the Jacobian times it: the columns of the
    large trees' looped Mt, J and residual Jacobians are such passes."""

    def test_equals_the_jacobian_times_the_direction(self):
        dx, dy = sp.symbols("dx dy")
        definitions, derivatives = directional_derivatives(
            PROGRAM, OUTPUTS, {x: dx, y: dy}, sp.numbered_symbols("d"))
        rng = random.Random(11)
        for _ in range(3):
            point = {s: sp.Float(rng.uniform(-2, 2), DIGITS) for s in (x, y, p, dx, dy)}
            values = dict(point)
            for symbol, expr in PROGRAM + definitions:
                values[symbol] = _value(expr).xreplace(values).evalf(DIGITS)
            for i, output in enumerate(OUTPUTS):
                flat = _flattened(output, PROGRAM)
                expected = (sp.diff(flat, x) * dx + sp.diff(flat, y) * dy).xreplace(
                    point).evalf(DIGITS)
                actual = _value(derivatives[i]).xreplace(values).evalf(DIGITS)
                self.assertLess(abs(actual - expected), 1e-20 * (1 + abs(expected)),
                                f"output {i}")

    def test_a_number_seed_is_a_partial_derivative(self):
        # seeding x alone with 1 is d/dx, y held fixed: forward_derivatives' column for x
        temporaries = sp.numbered_symbols("d")
        along_definitions, along = directional_derivatives(PROGRAM, OUTPUTS, {x: sp.Integer(1)},
                                                           temporaries)
        definitions, jacobian = forward_derivatives(PROGRAM, OUTPUTS, [x], temporaries)
        values = {x: sp.Float("0.3"), y: sp.Float("-1.1"), p: sp.Float("0.8")}
        for symbol, expr in PROGRAM + along_definitions + definitions:
            values[symbol] = _value(expr).xreplace(values).evalf(DIGITS)
        for i in range(len(OUTPUTS)):
            self.assertAlmostEqual(float(_value(along[i]).xreplace(values)),
                                   float(_value(jacobian[i][0]).xreplace(values)), places=12)


class AbsoluteValueTest(unittest.TestCase):
    """Intermediates carry no assumptions, yet every value is real: d|u| = u / |u| du, with
    no derivative of re(u) or im(u) left for the printer (a spring along one axis has
    length |s + 1|)."""

    def test_derivative_of_abs_of_an_intermediate(self):
        u = sp.Symbol("u")  # no real=True, as CSE's intermediates
        program = [(u, x * y + p)]
        definitions, jacobian = forward_derivatives(program, [sp.Abs(u) * y], [x],
                                                    sp.numbered_symbols("d"))
        values = {x: sp.Float("0.7"), y: sp.Float("-1.3"), p: sp.Float("0.2")}
        for symbol, expr in program + definitions:
            values[symbol] = _value(expr).xreplace(values)
        derivative = _value(jacobian[0][0])
        self.assertFalse(derivative.has(sp.Derivative, sp.re, sp.im), derivative)
        # d/dx |x y + p| y = sign(x y + p) y^2, and x y + p < 0 here
        self.assertAlmostEqual(float(derivative.xreplace(values)), -(1.3**2), places=12)


class FreeSymbolsTest(unittest.TestCase):
    """free_symbols_of, which partial() asks at every level, is SymPy's free_symbols."""

    def test_every_subexpression_agrees_with_sympy(self):
        q = sp.Function("q")(t[0])
        s = sp.Symbol("s")
        exprs = [*(e for _, e in PROGRAM), *OUTPUTS, sp.Abs(x * y + p) ** sp.Rational(3, 2),
                 sp.sin(q) * y + sp.Integer(2), sp.Integral(x * s, (s, 0, y)) * p,
                 sp.Derivative(q, t[0]) + x, sp.Float("0.5") * sp.pi]
        memo: dict = {}
        for expr in exprs:
            for sub in sp.preorder_traversal(expr):
                self.assertEqual(free_symbols_of(sub, memo), sub.free_symbols, sub)
        # the bound variable of the integral is not free
        self.assertNotIn(s, free_symbols_of(exprs[-3], memo))


class ChainSumPrintingTest(unittest.TestCase):

    def test_signs_parentheses_and_unit_factors(self):
        a, b, c, d = sp.symbols("a b c d")
        names = {s: s.name for s in (a, b, c, d, *t)}
        chain = ChainSum([(-2 * a, t[1]), (b, None), (c + d, t[2]), (sp.Integer(-1), t[3]),
                          (sp.Integer(1), t[4]), (-a * b, None)], {a, b, c, d, *t[1:5]})
        self.assertEqual(ScalarCxxPrinter(names).expression(chain),
                         "-Scalar(2)*a*t1 + b + (c + d)*t2 - t3 + t4 - a*b")
        # 5 additions; -2*a*t1 2, (c + d)*t2 2, -t3 1, -a*b 2: as many as the flat sum
        self.assertEqual(count_ops(chain), 12)
        self.assertEqual(count_ops(chain), count_ops(chain.as_expr()))

    def test_value_is_the_sum_of_its_terms(self):
        chain = ChainSum([(x, t[1]), (y, None)], {x, y, t[1]})
        self.assertEqual(chain.as_expr(), x * t[1] + y)


if __name__ == "__main__":
    unittest.main()
