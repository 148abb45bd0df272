# SPDX-License-Identifier: BSD-3-Clause
"""A wheel rolling without slipping on the ground plane z = 0: its constraint rows.

The wheel is a body with its centre c (a point of the body) and its axle a (a unit vector of
the body, R a in the world). The contact point is the wheel's lowest point,

    P = c + r d,   d = -(e_z - a_z a) / sqrt(1 - a_z^2),

the downward direction in the wheel's plane. Rolling without slipping is the velocity of the
wheel's material point at P being zero: v_P = c' + omega x (r d) = 0, with omega from
R' R^T = [omega]x. Its x and y components are velocity constraints; its z component vanishes
wherever the wheel touches the ground, P_z = 0, a holonomic constraint that the coordinates
may already satisfy (a wheel whose centre height is r times the cosine of its lean) or not (a
bicycle's front wheel, which sets the frame's pitch).
"""

from __future__ import annotations

import math
import random

import sympy as sp

from gencoord.dsl.frames import unskew
from gencoord.dsl.items import Body

SAMPLES = 16
SPREAD = 0.2  # rad (or m): the samples' distance from the initial coordinates


def _rate_of(expr: sp.Expr, q: list[sp.Symbol], rates: list[sp.Expr], t: sp.Symbol) -> sp.Expr:
    """d expr / dt along q' = rates."""
    return sp.Add(*[expr.diff(s) * rate for s, rate in zip(q, rates) if expr.has(s)]) + expr.diff(t)


def contact_rows(body: Body, radius: sp.Expr, axle: sp.Matrix, center: sp.Matrix,
                 q: list[sp.Symbol], rates: list[sp.Expr], t: sp.Symbol
                 ) -> tuple[list[sp.Expr], sp.Expr]:
    """([v_P,x, v_P,y], P_z) of the wheel: the no-slip rows and the contact height."""
    rotation = body.frame.rotation
    centre = body.frame.point(center)
    a = rotation * (axle / sp.sqrt(axle.dot(axle)))
    up = sp.Matrix([0, 0, 1])
    down = -(up - a[2] * a) / sp.sqrt(1 - a[2] ** 2)
    offset = radius * down
    omega = unskew(rotation.applyfunc(lambda e: _rate_of(e, q, rates, t)) * rotation.T)
    velocity = centre.applyfunc(lambda e: _rate_of(e, q, rates, t)) + omega.cross(offset)
    return [velocity[0], velocity[1]], (centre + offset)[2]


def vanishes_near(expr: sp.Expr, q: list[sp.Symbol], initial: list[float], t: sp.Symbol,
                  defaults: dict, scale: float, seed: int = 3) -> bool:
    """Whether expr is 0 (to 1e-12 of `scale`) at the initial coordinates and at random ones
    near them, parameters at their defaults (a contact height that the coordinates satisfy)."""
    value = sp.lambdify([q, t], expr.xreplace(defaults), modules="math")
    rng = random.Random(seed)
    points = [initial] + [[x + rng.uniform(-SPREAD, SPREAD) for x in initial]
                          for _ in range(SAMPLES)]
    try:
        return all(abs(value(point, rng.uniform(0, 1))) <= 1e-12 * scale for point in points)
    except (ValueError, ZeroDivisionError, OverflowError):
        return False


def positive_number(expr: sp.Expr, defaults: dict) -> float:
    """The value of expr at the default parameters, or 1 where that is not a positive number."""
    try:
        value = float(expr.xreplace(defaults))
    except (TypeError, ValueError):
        return 1.0
    return value if math.isfinite(value) and value > 0 else 1.0
