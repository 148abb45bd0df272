# SPDX-License-Identifier: BSD-3-Clause
"""Rotations and frames for rigid bodies: what a model file composes a body's pose from.

A `Frame` is a pose in the world: the rotation `R` that takes body axes to world axes and
the origin `p` of the body axes, so a point with body coordinates r sits at p + R r. Frames
compose like homogeneous transforms, `parent * child`, the child's pose given in the
parent's axes. In 2D the rotation is an angle and `R` the matching 2x2 matrix.

    R = rotation_z(yaw) * rotation_y(pitch) * rotation_x(roll)   # the same as rpy(roll, ...)
    link = Frame(R, [x, y, z]) * Frame(rotation_z(q1), [0, 0, 0.3])
"""

from __future__ import annotations

from typing import Sequence

import sympy as sp

from gencoord.symbolic.sums import product


def rotation_x(angle) -> sp.Matrix:
    """Rotation by `angle` about the x axis."""
    c, s = sp.cos(angle), sp.sin(angle)
    return sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])


def rotation_y(angle) -> sp.Matrix:
    """Rotation by `angle` about the y axis."""
    c, s = sp.cos(angle), sp.sin(angle)
    return sp.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rotation_z(angle) -> sp.Matrix:
    """Rotation by `angle` about the z axis."""
    c, s = sp.cos(angle), sp.sin(angle)
    return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def rotation_about(axis: str, angle) -> sp.Matrix:
    """Rotation by `angle` about the axis named "x", "y" or "z"."""
    return {"x": rotation_x, "y": rotation_y, "z": rotation_z}[axis](angle)


def rotation_2d(angle) -> sp.Matrix:
    """The 2x2 rotation by `angle` (counter-clockwise)."""
    c, s = sp.cos(angle), sp.sin(angle)
    return sp.Matrix([[c, -s], [s, c]])


def rpy(roll, pitch, yaw) -> sp.Matrix:
    """Roll about x, then pitch about the fixed y, then yaw about the fixed z (URDF's rpy):
    R = Rz(yaw) Ry(pitch) Rx(roll)."""
    return rotation_z(yaw) * rotation_y(pitch) * rotation_x(roll)


def axis_angle(axis: Sequence, angle) -> sp.Matrix:
    """Rotation by `angle` about `axis` (any nonzero length; it is normalized), Rodrigues'
    formula R = I + sin a K + (1 - cos a) K^2 with K the cross-product matrix of the unit axis.

    Numeric axes along x, y or z give the elementary rotations exactly (no sqrt terms).
    """
    u = sp.Matrix([sp.sympify(component) for component in axis])
    if u.shape != (3, 1):
        raise ValueError(f"an axis has 3 components, not {u.shape[0]}")
    length = sp.sqrt(u.dot(u))
    if length == 0:
        raise ValueError("the axis is zero; give a nonzero direction")
    u = u / length
    for k, elementary in enumerate((rotation_x, rotation_y, rotation_z)):
        if all(u[j] == (1 if j == k else 0) for j in range(3)):
            return elementary(angle)
        if all(u[j] == (-1 if j == k else 0) for j in range(3)):
            return elementary(-angle)
    K = skew(u)
    return sp.eye(3) + sp.sin(angle) * K + (1 - sp.cos(angle)) * K * K


def skew(w: Sequence) -> sp.Matrix:
    """The cross-product matrix [w]x, with [w]x r = w x r."""
    return sp.Matrix([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def unskew(S: sp.Matrix) -> sp.Matrix:
    """The vector w of a skew-symmetric matrix S = [w]x (read from its lower triangle)."""
    return sp.Matrix([S[2, 1], S[0, 2], S[1, 0]])


class Frame:
    """A pose: rotation (dim x dim matrix, or an angle in 2D) and origin (dim vector).

    In 2D `angle` keeps the angle, so a body's angular velocity is its time derivative.
    """

    def __init__(self, rotation, origin: Sequence):
        self.origin = sp.Matrix([sp.sympify(component) for component in origin])
        self.dim = self.origin.shape[0]
        if self.dim not in (2, 3):
            raise ValueError(f"a frame's origin has 2 or 3 components, not {self.dim}")
        self.angle = None
        if isinstance(rotation, sp.MatrixBase):
            self.rotation = sp.Matrix(rotation)
        elif self.dim == 2:
            self.angle = sp.sympify(rotation)
            self.rotation = rotation_2d(self.angle)
        else:
            self.rotation = sp.Matrix(rotation)
        if self.rotation.shape != (self.dim, self.dim):
            raise ValueError(f"a {self.dim}D frame's rotation is {self.dim}x{self.dim} "
                             f"(or an angle in 2D), not {self.rotation.shape[0]}x"
                             f"{self.rotation.shape[1]}")

    @classmethod
    def identity(cls, dim: int = 3) -> "Frame":
        return cls(0 if dim == 2 else sp.eye(3), [0] * dim)

    def __mul__(self, child: "Frame") -> "Frame":
        """The child's pose in the world, the child given in this frame's axes."""
        if child.dim != self.dim:
            raise ValueError("frames of different dimensions do not compose")
        origin = self.origin + product(self.rotation, child.origin)
        if self.dim == 2 and self.angle is not None and child.angle is not None:
            return Frame(self.angle + child.angle, origin)
        return Frame(product(self.rotation, child.rotation), origin)

    def inverse(self) -> "Frame":
        """The pose of the world in this frame: R^T and -R^T p."""
        transpose = self.rotation.T
        return Frame(transpose, list(-transpose * self.origin))

    def point(self, r: Sequence) -> sp.Matrix:
        """The world position of the point with body coordinates r: p + R r."""
        return self.origin + product(self.rotation, sp.Matrix([sp.sympify(c) for c in r]))
