# SPDX-License-Identifier: BSD-3-Clause
"""What a user expression may contain: finite real numbers and functions that are smooth
where they are defined, so that every derivative the generator takes exists there.

Refused, by name: numbers that are not finite (oo, nan, zoo) or not real (I); functions that
jump or kink (Abs, sign, Piecewise, floor, Heaviside, Min, Max ...) of anything that varies
(coordinates, velocities, time, point positions); unevaluated derivatives, integrals, sums
and limits. The same functions of parameters alone are constants and allowed: Abs(k) has
derivative 0 with respect to q.
"""

from __future__ import annotations

import sympy as sp

# jumps or kinks: their derivatives (sign, DiracDelta, Piecewise conditions) have no C++ form
NON_SMOOTH = (sp.Abs, sp.sign, sp.Piecewise, sp.floor, sp.ceiling, sp.Heaviside, sp.Max,
              sp.Min, sp.frac, sp.Mod, sp.DiracDelta, sp.re, sp.im, sp.arg, sp.conjugate)
UNEVALUATED = (sp.Derivative, sp.Integral, sp.Sum, sp.Product, sp.Limit, sp.Subs)


def _name(node) -> str:
    return type(node).__name__


def expression_problem(expr: sp.Basic, constants: set) -> str | None:
    """Why `expr` cannot be emitted (None: it can); `constants` are the parameter symbols."""
    for node in sp.preorder_traversal(expr):
        if isinstance(node, UNEVALUATED):
            return (f"contains an unevaluated {_name(node)} ({node}); evaluate it (.doit()) "
                    "or write its result, since the generator emits only closed forms")
        if node in (sp.nan, sp.zoo) or (node.is_Number and node.is_finite is False):
            return (f"contains {node}, which is not a finite number (a division by zero, an "
                    "infinite or NaN value?); every number of a model must be finite")
        if node is sp.I:
            return "contains the imaginary unit I; models are real"
        if isinstance(node, NON_SMOOTH):
            varying = sorted(str(s) for s in node.free_symbols - constants)
            if varying:
                return (f"{_name(node)} of {', '.join(varying)} ({node}) is not a smooth "
                        "function, and the generator differentiates every expression of "
                        "q, v and t; write a smooth expression (for Abs(u) where the sign of "
                        "u is known: u or -u), or split the model where it changes")
    return None
