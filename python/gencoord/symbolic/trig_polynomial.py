# SPDX-License-Identifier: BSD-3-Clause
"""Expressions of sin, cos and tan as polynomials on circles: cheap exact proofs that one
vanishes identically, and the form singularities.py factors det(J^T J) in.

Each distinct argument a of sin/cos/tan becomes a pair of symbols (s, c) with s^2 + c^2 = 1
(tan a = s / c); the numerator is then a polynomial, and division by s^2 + c^2 - 1 in each
pair's s leaves a remainder of degree < 2 in s that is zero exactly when the polynomial
vanishes on every circle. This replaces trigsimp, which expands sums of angles and took
tens of seconds on a 6-coordinate rigid body. Arguments are treated as independent, so a
zero remainder proves the identity; a nonzero one proves nothing (theta and 2 theta are not
independent): callers then sample.
"""

from __future__ import annotations

from typing import Any

import sympy as sp
from sympy.polys.polyerrors import GeneratorsNeeded, PolynomialError

MAX_TERMS = 4000           # a bigger polynomial is not worth proving: sample it instead
FLOAT_ROUND_OFF = 1e-12    # relative size of a coefficient that counts as zero with Floats


def circle_symbols(expr) -> tuple[Any, list[tuple[sp.Symbol, sp.Symbol]], dict]:
    """expr (an expression or a matrix) with sin/cos/tan of each argument replaced by s_k,
    c_k, s_k / c_k; the (s_k, c_k) pairs; the map from them back to sin/cos."""
    functions = expr.atoms(sp.sin, sp.cos, sp.tan)
    arguments = sorted({f.args[0] for f in functions}, key=sp.default_sort_key)
    pairs = [(sp.Dummy(f"s{k}", real=True), sp.Dummy(f"c{k}", real=True))
             for k in range(len(arguments))]
    of = dict(zip(arguments, pairs))
    replacement = {}
    for f in functions:
        s, c = of[f.args[0]]
        replacement[f] = s if f.func is sp.sin else c if f.func is sp.cos else s / c
    back = {}
    for argument, (s, c) in of.items():
        back[s], back[c] = sp.sin(argument), sp.cos(argument)
    return expr.xreplace(replacement), pairs, back


def reduce_on_circles(poly: sp.Poly, pairs) -> sp.Poly:
    """The remainder of poly on division by s^2 + c^2 - 1 in each pair's s: the same
    function on the circles, of degree < 2 in every s."""
    for s, c in pairs:
        if s in poly.gens and c in poly.gens:
            others = [g for g in poly.gens if g != s]
            poly = sp.Poly(poly, s, *others).rem(sp.Poly(s**2 + c**2 - 1, s, *others))
    return poly


def vanishes_identically(expr) -> bool:
    """True when expr is proven zero for every value of its symbols; False: not proven."""
    expr = sp.sympify(expr)
    if expr == 0:
        return True
    replaced, pairs, _ = circle_symbols(expr)
    numerator = sp.fraction(sp.together(replaced))[0] if replaced.has(sp.Pow) else replaced
    numerator = sp.expand(numerator)
    if numerator.is_number:
        return numerator == 0
    try:
        poly = sp.Poly(numerator)
    except (PolynomialError, GeneratorsNeeded, sp.SympifyError, TypeError):
        return False
    if len(poly.terms()) > MAX_TERMS:
        return False
    try:
        scale = max(abs(float(c)) for c in poly.coeffs())
        poly = reduce_on_circles(poly, pairs)
        if poly.is_zero or poly.domain.is_Exact:
            return poly.is_zero
        return max(abs(float(c)) for c in poly.coeffs()) <= FLOAT_ROUND_OFF * scale
    except (PolynomialError, TypeError, ValueError):  # coefficients that are not numbers
        return False
