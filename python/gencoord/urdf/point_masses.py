# SPDX-License-Identifier: BSD-3-Clause
"""Point-mass links: a link whose <inertia> is zero (a 1 g IMU, a foot's contact point) is no
rigid body the model can build, but on a fixed joint it is part of its parent's: its mass is
folded into the parent's inertial (mass, centre and inertia about the new centre), as
MuJoCo's compiler fuses static bodies. Its link stays, massless, with its frame and geometry.
On a moving joint a point mass is refused: a link that turns needs a tensor.
"""

from __future__ import annotations

import dataclasses

import sympy as sp

from gencoord.dsl.frames import rpy
from gencoord.dsl.joint_types import Origin
from gencoord.errors import ModelError


def is_zero_tensor(inertia: sp.Matrix) -> bool:
    """A point mass's inertia: every entry zero."""
    return all(sp.sympify(value).is_zero for value in inertia)


def _numbers(matrix: sp.Matrix) -> sp.Matrix:
    return matrix.applyfunc(lambda value: sp.Float(float(value)))


def _in_link_axes(inertial) -> tuple[sp.Matrix, sp.Matrix]:
    """(centre, inertia about the centre) of an inertial, both in its link's axes."""
    rotation = _numbers(rpy(*inertial.origin.rpy))
    return (_numbers(sp.Matrix(inertial.origin.xyz)),
            rotation * _numbers(inertial.inertia) * rotation.T)


def _shifted(mass, inertia: sp.Matrix, offset: sp.Matrix) -> sp.Matrix:
    """The inertia about a point `offset` away from the centre (parallel axes)."""
    return inertia + mass * (offset.dot(offset) * sp.eye(3) - offset * offset.T)


def fold_point_masses(robot) -> None:
    """Adds every point-mass link on a fixed joint to its parent's inertial (leaves first, so
    a chain of them folds up to the first link with a tensor), leaving it massless."""
    parents = robot.joints  # by the child link's name
    for name in reversed(robot.order()):
        link = robot.links[name]
        if link.inertial is None or not is_zero_tensor(link.inertial.inertia):
            continue
        joint = parents.get(name)
        if joint is None or joint.kind != "fixed":
            raise ModelError("a point mass (a zero <inertia>) on a moving joint or at the root "
                             "is no rigid body: give its inertia tensor, or weld it to a link "
                             "with a fixed joint", item=f"link '{name}'", filename=robot.path,
                             line=link.line)
        parent = robot.links[joint.parent]
        frame = joint.joint.origin.frame()
        position = _numbers(frame.point(list(link.inertial.origin.xyz)))
        mass = float(link.inertial.mass)
        if parent.inertial is None:
            parent.inertial = dataclasses.replace(
                link.inertial, origin=Origin(xyz=[float(v) for v in position]))
        else:
            total = float(parent.inertial.mass) + mass
            centre, inertia = _in_link_axes(parent.inertial)
            new_centre = (float(parent.inertial.mass) * centre + mass * position) / total
            inertia = (_shifted(float(parent.inertial.mass), inertia, centre - new_centre)
                       + _shifted(mass, sp.zeros(3, 3), position - new_centre))
            parent.inertial = dataclasses.replace(
                parent.inertial, mass=total, inertia=inertia,
                origin=Origin(xyz=[float(v) for v in new_centre]))
        link.inertial = None
