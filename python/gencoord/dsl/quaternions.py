# SPDX-License-Identifier: BSD-3-Clause
"""Unit quaternions q = (w, x, y, z), scalar first: the rotation they give and the rate of q
for an angular velocity given in the rotated (body) axes.

    R(q) = I + 2 w [u]x + 2 [u]x^2,  u = (x, y, z)      (orthogonal when |q| = 1)
    q' = 1/2 q (x) (0, omega)

R is written in the form that is exact on the unit sphere and polynomial off it. The runtime
divides q by its norm after each step; within a step (Runge-Kutta stages, Newton iterates)
the kernels see quaternions a little off the sphere, where R and G are smooth, and the exact
flow keeps |q| constant, so every method keeps its order.
"""

from __future__ import annotations

import math
from typing import Sequence

import sympy as sp


def quaternion_rotation(q: Sequence) -> sp.Matrix:
    """R(q): body axes to world axes."""
    w, x, y, z = q
    return sp.Matrix([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def quaternion_rate(q: Sequence, omega: Sequence) -> list[sp.Expr]:
    """q' = 1/2 q (x) (0, omega), omega in the body's axes."""
    w, x, y, z = q
    a, b, c = omega
    return [-(x * a + y * b + z * c) / 2, (w * a + y * c - z * b) / 2,
            (w * b + z * a - x * c) / 2, (w * c + x * b - y * a) / 2]


def quaternion_from_rpy(roll: float, pitch: float, yaw: float) -> list[float]:
    """The unit quaternion of rpy(roll, pitch, yaw) = Rz(yaw) Ry(pitch) Rx(roll), w >= 0."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp_ = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    q = [cy * cp * cr + sy * sp_ * sr, cy * cp * sr - sy * sp_ * cr,
         cy * sp_ * cr + sy * cp * sr, sy * cp * cr - cy * sp_ * sr]
    return [-c for c in q] if q[0] < 0 else q
