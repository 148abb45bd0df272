# SPDX-License-Identifier: BSD-3-Clause
"""The kinds of joint a link hangs from (joints.py builds the tree): revolute, continuous,
prismatic, fixed, and the quaternion joints, ball (a spherical joint: a unit quaternion,
the angular velocity as speeds) and free (position and unit quaternion, the body twist as
speeds), whose coordinates' rates are not speeds (speeds.py).

A joint's `origin` places its joint frame in the parent link's frame (translation xyz, then
rotation rpy); a free joint has no joint frame: its origin is the link's initial pose in the
parent's.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Sequence

import sympy as sp

from gencoord.dsl.frames import Frame, axis_angle, rpy

# an angle this close to a multiple of pi/2 (relative) is that multiple: below double
# precision, and the exact rotation keeps zeros out of every expression built on it
_RIGHT_ANGLE_TOLERANCE = 1e-12


def identifier(name: str) -> str:
    """A C++ identifier close to `name`: other characters become _, a leading digit gets a
    prefix."""
    text = re.sub(r"[^A-Za-z0-9_]", "_", name) or "unnamed"
    return text if not text[0].isdigit() else "j_" + text


def number(value):
    """A literal for an expression: an integer when the float is one (exact zeros and ones
    keep expressions small), else a Float; SymPy expressions are kept."""
    if isinstance(value, sp.Basic):
        return value
    value = float(value)
    return sp.Integer(int(value)) if value.is_integer() else sp.Float(value)


def angle(value):
    """A literal angle, exact when it is a multiple of pi/2 to within double precision."""
    if isinstance(value, sp.Basic):
        return value
    value = float(value)
    quarter_turns = round(value / (math.pi / 2))
    if abs(value - quarter_turns * math.pi / 2) <= _RIGHT_ANGLE_TOLERANCE * max(1.0, abs(value)):
        return quarter_turns * sp.pi / 2
    return number(value)


@dataclass
class Origin:
    """A pose in a parent frame: translation `xyz`, then rotation rpy(roll, pitch, yaw)."""
    xyz: Sequence = (0, 0, 0)
    rpy: Sequence = (0, 0, 0)

    def __post_init__(self):
        self.xyz = tuple(number(v) for v in self.xyz)
        self.rpy = tuple(angle(v) for v in self.rpy)
        if len(self.xyz) != 3 or len(self.rpy) != 3:
            raise ValueError("an origin's xyz and rpy have 3 components each")

    def frame(self) -> Frame:
        return Frame(rpy(*self.rpy), self.xyz)


@dataclass
class Limits:
    """A joint's range and ratings as URDF gives them: the range is enforced while the model
    runs; a speed above the velocity rating, and a generalized force of the control inputs
    above the effort rating, are reported (joint_limits.py)."""
    lower: float | None = None
    upper: float | None = None
    effort: float | None = None
    velocity: float | None = None

    def __str__(self) -> str:
        parts = []
        if self.lower is not None or self.upper is not None:
            parts.append(f"limits [{_text(self.lower)}, {_text(self.upper)}]")
        if self.effort is not None:
            parts.append(f"effort {_text(self.effort)}")
        if self.velocity is not None:
            parts.append(f"velocity {_text(self.velocity)}")
        return ", ".join(parts)


def _text(value) -> str:
    return "-" if value is None else f"{value:g}"


@dataclass
class Joint:
    """A joint's placement in its parent link; `name` names its coordinate (default: the
    child link's name and _joint)."""
    origin: Origin = field(default_factory=Origin)
    name: str | None = field(default=None, kw_only=True)

    kind = "joint"
    unit = ""

    def moves(self) -> bool:
        return False

    def motion(self, q) -> Frame:
        """The child link's frame in the joint frame at coordinate q."""
        return Frame.identity()


@dataclass
class Mimic:
    """A joint that follows another (URDF <mimic>): its value is multiplier * q + offset, q the
    followed joint's coordinate; it has no coordinate of its own."""
    coordinate: sp.Symbol
    multiplier: float = 1.0
    offset: float = 0.0


@dataclass(init=False)
class _Moving(Joint):
    """A joint with a coordinate: it moves about or along `axis` (joint-frame components); with
    `mimic`, by the followed joint's coordinate instead of one of its own. `damping` c resists
    its rate qdot with -c qdot, `friction` F (Coulomb's, a torque or a force) with the smooth
    -F tanh(qdot / s), s the model's parameter joint_friction_speed (joints.py)."""
    axis: Sequence = (1, 0, 0)
    limits: Limits | None = None
    damping: float = 0
    mimic: Mimic | None = None
    friction: float = 0

    def __init__(self, axis: Sequence, origin: Origin | None = None,
                 limits: Limits | None = None, damping=0, name: str | None = None,
                 mimic: Mimic | None = None, friction=0):
        self.axis = tuple(number(v) for v in axis)
        self.origin = origin if origin is not None else Origin()
        self.limits, self.damping, self.name = limits, number(damping), name
        self.mimic, self.friction = mimic, number(friction)

    def moves(self) -> bool:
        return True

    def unit_axis(self) -> sp.Matrix:
        axis = sp.Matrix(self.axis)
        return axis / sp.sqrt(axis.dot(axis))


class Revolute(_Moving):
    """A rotation by q about `axis` (through the joint frame's origin), within `limits`."""
    kind = "revolute"
    unit = "rad"

    def motion(self, q) -> Frame:
        return Frame(axis_angle(self.axis, q), [0, 0, 0])


class Continuous(Revolute):
    """A revolute joint without a range."""
    kind = "continuous"


class Prismatic(_Moving):
    """A translation by q along `axis`."""
    kind = "prismatic"
    unit = "m"

    def motion(self, q) -> Frame:
        return Frame(sp.eye(3), list(self.unit_axis() * q))


class Fixed(Joint):
    """A weld: the child link's frame is the joint frame."""
    kind = "fixed"


class _QuaternionJoint(Joint):
    """A joint whose rotation is a unit quaternion (quaternions.py): no axis, no range."""
    limits = None
    damping = 0

    def moves(self) -> bool:
        return True


class Ball(_QuaternionJoint):
    """A spherical joint at the joint frame's origin: the child turns freely about it.
    Coordinates: a unit quaternion (w, x, y, z), the child's axes in the joint frame's;
    speeds: the child's angular velocity relative to its parent, in the child's axes."""
    kind = "ball"


class Free(_QuaternionJoint):
    """No joint: the child moves freely in its parent's frame (the world's for a root link).
    Coordinates: the link origin's position (x, y, z) and a unit quaternion (w, x, y, z), the
    link's axes in the parent's; speeds: the body twist, the link origin's velocity and the
    angular velocity, both in the link's axes. `origin` is the initial pose."""
    kind = "free"
