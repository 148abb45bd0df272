# SPDX-License-Identifier: BSD-3-Clause
"""Whether a body's frame rotation is a rotation: R^T R = I and det R = 1.

A matrix that is not (2 Rz Rx, a shear, a non-orthogonal 2x2) would be taken for one and
silently change the body's kinetic energy. It is checked numerically at the default
parameters and a few seeded configurations, which catches any constant or generic defect.
Frames that joints.py composes from rotation_x/y/z, rpy and axis_angle are rotations by
construction and are not checked.
"""

from __future__ import annotations

import math
import random

import sympy as sp

SAMPLES = 3
TOLERANCE = 1e-9


def _number(expr: sp.Expr) -> float | None:
    """A real, finite value of a closed expression, else None."""
    try:
        value = complex(expr.evalf())
    except (TypeError, ValueError):
        return None
    if abs(value.imag) > 1e-12 or not math.isfinite(value.real):
        return None
    return value.real


def _sample(symbols: list[sp.Symbol], rng: random.Random) -> dict:
    return {symbol: sp.Float(rng.uniform(-1.5, 1.5)) for symbol in symbols}


def rotation_problem(rotation: sp.Matrix, variables: list[sp.Symbol],
                     defaults: dict) -> str | None:
    """What is wrong with `rotation` (a function of `variables` and parameters), or None."""
    rng = random.Random(20240601)
    n = rotation.shape[0]
    fixed = rotation.xreplace(defaults)
    for _ in range(SAMPLES):
        at = _sample(variables, rng)
        numbers = [[_number(fixed[i, j].xreplace(at)) for j in range(n)] for i in range(n)]
        if any(value is None for row in numbers for value in row):
            return None  # outside the expression's domain: the other checks report that
        values = [[float(value or 0.0) for value in row] for row in numbers]
        gram = max(abs(sum(values[k][i] * values[k][j] for k in range(n)) - (i == j))
                   for i in range(n) for j in range(n))
        det = float(sp.Matrix(values).det())
        if gram > TOLERANCE or abs(det - 1) > TOLERANCE:
            where = ", ".join(f"{symbol} = {float(value):.3g}" for symbol, value in at.items())
            kind = "not orthonormal" if gram > TOLERANCE else "a reflection (det R = -1)"
            return (f"rotation is {kind}: R^T R differs from the identity by {gram:.3g} and "
                    f"det R = {det:.6g} at {where or 'every configuration'} (with the default "
                    "parameters); compose it from rotation_x/y/z, rpy or axis_angle, or give "
                    "an orthonormal matrix with determinant 1")
    return None
