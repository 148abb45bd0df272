# SPDX-License-Identifier: BSD-3-Clause
"""Spatial vectors of rigid-body dynamics, 6 x 1 in a link's own axes.

Motions are (omega; v), v the velocity of the frame's origin; forces are (moment about the
origin; force). A link's frame in its parent's is (E, r): E the child's axes in the parent's,
r the child's origin in the parent's axes. These are the transformations and products the
recursions of body_recursion.py are written in.
"""

from __future__ import annotations

import sympy as sp

from gencoord.dsl.frames import skew
from gencoord.symbolic.sums import product


def split(vector: sp.Matrix) -> tuple[sp.Matrix, sp.Matrix]:
    """(angular; linear) parts of a spatial vector."""
    return vector[:3, 0], vector[3:, 0]


def motion_to_child(E: sp.Matrix, r: sp.Matrix, motion: sp.Matrix) -> sp.Matrix:
    """X m: a motion in the parent's axes at its origin, in the child's at the child's."""
    w, v = split(motion)
    return sp.Matrix.vstack(product(E.T, w), product(E.T, v + w.cross(r)))


def force_to_parent(E: sp.Matrix, r: sp.Matrix, force: sp.Matrix) -> sp.Matrix:
    """X^T f: a force in the child's axes about its origin, in the parent's about its own."""
    n, f = split(force)
    f_parent = product(E, f)
    return sp.Matrix.vstack(product(E, n) + r.cross(f_parent), f_parent)


def cross_motion(V: sp.Matrix, motion: sp.Matrix) -> sp.Matrix:
    """V x m."""
    w, v = split(V)
    w2, v2 = split(motion)
    return sp.Matrix.vstack(w.cross(w2), w.cross(v2) + v.cross(w2))


def cross_force(V: sp.Matrix, force: sp.Matrix) -> sp.Matrix:
    """V x* f."""
    w, v = split(V)
    n, f = split(force)
    return sp.Matrix.vstack(w.cross(n) + v.cross(f), w.cross(f))


def inertia_to_parent(E: sp.Matrix, r: sp.Matrix, inertia: sp.Matrix,
                      names=None) -> sp.Matrix:
    """X^T I X for a symmetric 6 x 6 I = [[A, B], [B^T, C]]: rotated into the parent's axes,
    then moved to its origin (blocks A + R B^T - B R - R C R, B + R C, C with R = [r]x).

    Given `names` (structured.Intermediates), the rotated blocks and R C are named, so the
    products after them are of symbols rather than of sums of 27 terms."""
    A, B, C = inertia[:3, :3], inertia[:3, 3:], inertia[3:, 3:]
    A, B, C = (product(product(E, block), E.T) for block in (A, B, C))
    if names:
        A, B, C = names.symmetric(A), names.matrix(B), names.symmetric(C)
    R = skew(r)
    RC = names.matrix(product(R, C)) if names else product(R, C)
    return sp.Matrix.vstack(
        sp.Matrix.hstack(A + product(R, B.T) - product(B, R) - product(RC, R), B + RC),
        sp.Matrix.hstack((B + RC).T, C))


def rigid_inertia(mass, com: sp.Matrix, inertia_at_com: sp.Matrix) -> sp.Matrix:
    """The spatial inertia about a frame's origin of a body of `mass` centred at `com`, with
    `inertia_at_com` about its centre of mass; all in that frame's axes."""
    C = skew(com)
    return sp.Matrix.vstack(
        sp.Matrix.hstack(inertia_at_com + mass * C * C.T, mass * C),
        sp.Matrix.hstack(mass * C.T, mass * sp.eye(3)))
