# SPDX-License-Identifier: BSD-3-Clause
"""Kinematic trees: links joined by revolute, continuous, prismatic and fixed joints.

`add_link` composes a link's frame from its parent's (URDF's conventions), declares the
joint's coordinate, the link's body, the joint's damping and friction and the pins that hold
the joint together in the maximal-coordinate model:

    turret = add_link(model, "turret", None, Revolute([0, 0, 1], Origin(xyz=[0, 0, 0.1])),
                      mass=4.0, inertia=I0)
    arm = add_link(model, "arm", turret, Revolute([0, 1, 0], Origin(xyz=[0, 0, 0.3])),
                   mass=2.0, inertia=I1, com=Origin(xyz=[0, 0, 0.2]))

The joint frame is the parent link's frame times `origin` (translation xyz, rotation
rpy(roll, pitch, yaw)); the joint moves about or along `axis`, given in the joint frame; the
child link's frame is the moved joint frame. A link's body sits at `com` in the link frame,
its inertia given in the axes of `com`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from gencoord.errors import ModelError
from gencoord.dsl.frames import Frame, rotation_about
from gencoord.dsl.items import Body
from gencoord.dsl.joint_types import (Ball, Continuous, Fixed, Free, Joint, Limits, Mimic, Origin,
                                      Prismatic, Revolute, _Moving, _QuaternionJoint,
                                      identifier, number)
from gencoord.dsl.quaternions import (quaternion_from_rpy, quaternion_rate,
                                      quaternion_rotation)

__all__ = ["Ball", "Continuous", "Fixed", "Free", "Joint", "Limits", "Mimic", "Origin", "Prismatic",
           "Revolute", "Link", "add_link", "add_free_base", "identifier", "number"]

# Joint friction's smoothing speed s, a parameter of the model (Params changes it at run
# time): -F tanh(qdot / s) acts like a damping F / s near rest, which an explicit step must
# resolve, so the default is a speed a robot's joints pass through quickly, not a tiny one.
FRICTION_SPEED = 0.1
FRICTION_SPEED_DESCRIPTION = ("speed at which joint friction -F tanh(qdot / s) reaches 76% of "
                              "F (rad/s or m/s)")

# Euler-angle charts of a free-floating base: each angle's name, axis and description,
# outermost (world) first; the two charts' singular sets are disjoint (see atlas.py).
EULER_CHARTS = {
    "zyx": [("yaw", "z", "rotation about z (rad)"),
            ("pitch", "y", "rotation about the new y (rad)"),
            ("roll", "x", "rotation about the new x (rad)")],
    "yzx": [("heading", "y", "rotation about y (rad)"),
            ("attitude", "z", "rotation about the new z (rad)"),
            ("bank", "x", "rotation about the new x (rad)")],
}


@dataclass
class Link:
    """A link of the tree: its world frame, its body (None when massless or welded to the
    world) and its joint's coordinate (None for a fixed joint)."""
    name: str
    frame: Frame
    joint: Joint | None
    parent: "Link | None"
    body: Body | None = None
    coordinate: sp.Symbol | None = None
    coordinates: list = field(default_factory=list)
    # v of its joint: its coordinates' rates, or a quaternion joint's twist (speeds.py)
    speeds: list = field(default_factory=list)
    limits: Limits | None = None
    # a URDF link's visual and collision elements, for the viewer; dynamics ignores them
    # (None: the link was not read from a URDF)
    geometry: list | None = None
    # what holds this link's frame rigidly: (body or None for the world, this frame in that
    # body's axes -- or in the world's), None when a moving massless link lies in between
    support: tuple | None = None
    # why the maximal model has no pins for this link's joint ('' when it has)
    unpinned: str = ""
    # this link's frame in its parent link's (the world's for a root): what the joint moves
    local: Frame | None = None
    # the body's frame (centre of mass, inertia axes) in this link's frame
    inertial: Frame | None = None


def _grounded(frame: Frame, model) -> bool:
    """True when nothing in the frame depends on a coordinate: the link cannot move."""
    coordinates = {c.symbol for c in model.coordinates}
    symbols = frame.rotation.free_symbols | frame.origin.free_symbols
    return not (symbols & coordinates)


def _unused(model, name: str, suffix: str) -> str:
    """`name`, with `suffix` appended while the model already uses it: URDF names links and
    joints apart, so a link and its joint may share a name."""
    taken = {item.name for item in [*model.coordinates, *model.speeds, *model.parameters,
                                    *model.bodies, *model.points]}
    while name in taken:
        name += suffix
    return name


def _declare_body(model, name: str, frame: Frame, mass, inertia, com: Origin,
                  label: str) -> tuple[Body, Frame]:
    """The link's body at its centre of mass, and the body's frame in the link's."""
    if not isinstance(com, Origin):
        raise ModelError("com is an Origin(xyz=..., rpy=...) in the link frame", item=label)
    inertial = com.frame()
    body = model.body(_unused(model, identifier(name), "_body"), number(mass),
                      sp.Matrix(inertia), frame * inertial)
    return body, inertial


def _check_axis(joint: Joint, label: str) -> None:
    if isinstance(joint, _Moving):
        if len(joint.axis) != 3:
            raise ModelError(f"the axis has {len(joint.axis)} components; give 3", item=label)
        if all(sp.sympify(v) == 0 for v in joint.axis):
            raise ModelError("the axis is zero; give the direction the joint moves about or "
                             "along, e.g. [0, 0, 1]", item=label)


def _check_resistances(joint: Joint, label: str) -> None:
    """Damping and friction must not feed energy in: a negative value is refused."""
    if isinstance(joint, _Moving):
        for what, given in (("damping", joint.damping), ("friction", joint.friction)):
            value = sp.sympify(given)  # number() made it a SymPy number or expression
            if value.is_number and value.is_negative:
                raise ModelError(f"the {what} is {float(value):g}; give a non-negative {what}",
                                 item=label)


def add_link(model, name: str, parent: Link | None, joint: Joint, mass=None, inertia=None,
             com: Origin | None = None) -> Link:
    """Adds link `name`, joined to `parent` (None: the world) by `joint`; with `mass`, the
    link is a body whose `inertia` (3x3, about the centre of mass) is given in `com`'s axes.

    The joint's coordinate is named after the joint; a moving joint's damping c adds the
    generalized force -c qdot, its friction F the smoothed Coulomb friction -F tanh(qdot / s)
    (`_friction_speed`). Returns the Link.
    """
    com = com if com is not None else Origin()
    if not isinstance(joint, Joint):
        raise ModelError("give a Revolute, Continuous, Prismatic, Fixed, Ball or Free joint",
                         item=f"link '{name}'")
    if parent is not None and not isinstance(parent, Link):
        raise ModelError("the parent is a Link that add_link returned, or None for the world",
                         item=f"link '{name}'")
    if (mass is None) != (inertia is None):
        raise ModelError("give both mass and inertia (a body), or neither (a massless link)",
                         item=f"link '{name}'")
    joint_label = joint.name or f"{name}_joint"
    label = f"joint '{joint_label}'"
    _check_axis(joint, label)
    _check_resistances(joint, label)
    parent_frame = parent.frame if parent else Frame.identity()
    joint_frame = parent_frame * joint.origin.frame()
    joint_name = _unused(model, identifier(joint_label), "_q")
    q = None
    if isinstance(joint, _QuaternionJoint):
        if model.dim != 3:
            raise ModelError(f"a {joint.kind} joint needs a 3D model: Model(dim=3)", item=label)
        coordinates, speeds, local = _quaternion_joint(model, identifier(name), joint, label)
        if isinstance(joint, Free):
            joint_frame = parent_frame  # a free joint's origin is the initial pose
        link = Link(name, parent_frame * local, joint, parent, coordinates=coordinates,
                    speeds=speeds, local=local)
    else:
        q, value = _joint_value(model, joint, joint_name, joint_label, label)
        local = joint.origin.frame() * joint.motion(value)
        link = Link(name, joint_frame * joint.motion(value), joint, parent, coordinate=q,
                    coordinates=[q] if q is not None else [],
                    speeds=[model.rate(q)] if q is not None else [],
                    limits=getattr(joint, "limits", None), local=local)
    model.links.append(link)
    if _grounded(link.frame, model):
        link.support = (None, link.frame)  # welded to the world: its mass does nothing
    elif mass is not None:
        link.body, link.inertial = _declare_body(model, name, link.frame, mass, inertia, com,
                                                 f"link '{name}'")
        link.support = (link.body, link.inertial.inverse())
    elif not joint.moves() and parent is not None and parent.support is not None:
        body, offset = parent.support
        link.support = (body, offset * joint.origin.frame())
    if isinstance(joint, _Moving):
        _add_resistances(model, link, joint, joint_frame, joint_name, label)
    if link.body is not None:
        _pin(model, link, parent, joint, joint_name)
    return link


def _quaternion_joint(model, name: str, joint: _QuaternionJoint, label: str
                      ) -> tuple[list[sp.Symbol], list[sp.Symbol], Frame]:
    """A ball or free joint's coordinates, speeds and rates (named after its link), and the
    link's frame in its parent's."""
    free = isinstance(joint, Free)
    pose = [float(value) for value in (*joint.origin.xyz, *joint.origin.rpy)] if free else []
    position = []
    if free:
        position = [model.coordinate(_unused(model, f"{name}_{axis}", "_q"),
                                     f"{label}: position of the link origin, {axis} (m)",
                                     initial=value, has_speed=False)
                    for axis, value in zip("xyz", pose)]
    start = len(model.coordinates)
    initial = quaternion_from_rpy(*pose[3:]) if free else [1.0, 0.0, 0.0, 0.0]
    quaternion = [model.coordinate(_unused(model, f"{name}_q{part}", "_q"),
                                   f"{label}: unit quaternion, {part} (scalar first)",
                                   initial=value, has_speed=False)
                  for part, value in zip("wxyz", initial)]
    model.quaternions.append(start)
    linear = [model.speed(_unused(model, f"{name}_v{axis}", "_q"),
                          f"{label}: velocity of the link origin along the link's {axis} (m/s)")
              for axis in ("xyz" if free else "")]
    angular = [model.speed(_unused(model, f"{name}_w{axis}", "_q"),
                           f"{label}: angular velocity about the link's {axis} (rad/s)")
               for axis in "xyz"]
    rotation = quaternion_rotation(quaternion)
    model.rates.update(zip(quaternion, quaternion_rate(quaternion, angular)))
    if free:
        model.rates.update(zip(position, rotation * sp.Matrix(linear)))
        return position + quaternion, linear + angular, Frame(rotation, position)
    return quaternion, angular, joint.origin.frame() * Frame(rotation, [0, 0, 0])


def _joint_value(model, joint: Joint, joint_name: str, joint_label: str, label: str
                 ) -> tuple[sp.Symbol | None, sp.Expr | None]:
    """A revolute or prismatic joint's coordinate (declared here, with its limits) and value:
    the coordinate, or for a mimic joint none and the followed coordinate, mapped; neither
    for a fixed joint."""
    if not isinstance(joint, _Moving):
        return None, None
    if joint.mimic is not None:
        return None, _followed(model, joint, label)
    description = f"{joint.kind} joint '{joint_label}' ({joint.unit})"
    if joint.limits is not None and str(joint.limits):
        description += f", {joint.limits}"
    q = model.coordinate(joint_name, description, initial=_initial(joint.limits))
    if joint.limits is not None:
        _limit(model, q, joint, joint_label)
    return q, q


def _followed(model, joint: _Moving, label: str) -> sp.Expr:
    """A mimic joint's value, multiplier * q + offset, q the followed joint's coordinate."""
    mimic = joint.mimic
    assert mimic is not None  # called for a mimic joint
    followed = model._coordinate_of(mimic.coordinate, label, None)
    ranged = joint.limits is not None and (joint.limits.lower is not None
                                           or joint.limits.upper is not None)
    if ranged and not isinstance(joint, Continuous):
        model.ignored.append(f"{label}: a mimic joint's range (the followed joint's holds it)")
    return number(mimic.multiplier) * followed.symbol + number(mimic.offset)


def _add_resistances(model, link: Link, joint: _Moving, joint_frame: Frame, joint_name: str,
                     label: str) -> None:
    """The joint's damping -c qdot and friction -F tanh(qdot / s), where it has them."""
    if joint.damping != 0:
        _resist(model, link, joint_frame, lambda rate: -joint.damping * rate,
                f"{joint_name}_damping", "damping", label)
    if joint.friction != 0:
        speed = _friction_speed(model)
        _resist(model, link, joint_frame, lambda rate: -joint.friction * sp.tanh(rate / speed),
                f"{joint_name}_friction", "friction", label)


def _friction_speed(model) -> sp.Symbol:
    """The parameter s of every joint's smoothed Coulomb friction -F tanh(qdot / s), declared
    with the first joint that has friction: the friction reaches 76% of F at |qdot| = s and
    99.9% at 4 s. A smaller s is closer to Coulomb's law and stiffer to integrate (the slope
    F / s at rest acts as a damping)."""
    if model.joint_friction_speed is None:
        model.joint_friction_speed = model.parameter(
            _unused(model, "joint_friction_speed", "_"), FRICTION_SPEED,
            FRICTION_SPEED_DESCRIPTION)
    return model.joint_friction_speed


def _resist(model, link: Link, joint_frame: Frame, law, name: str, what: str,
            label: str) -> None:
    """A force of the joint's rate alone, law(qdot) (damping, friction), on its coordinate; in
    a chart of an atlas, which refuses forces on q, the same as torques +-law(qdot) about the
    joint axis on the two bodies (their virtual work is law(qdot) dq). A mimic joint's rate is
    m qdot, q the coordinate it follows, and its virtual displacement m dq: m law(m qdot) on q."""
    joint = link.joint
    assert isinstance(joint, _Moving)  # only a moving joint has a rate
    if joint.mimic is not None:
        if model.chart:
            raise ModelError(f"in an atlas, a mimic joint's {what} is not supported; set it to 0",
                             item=label)
        multiplier = number(joint.mimic.multiplier)
        followed = joint.mimic.coordinate
        model.generalized_force(followed, multiplier * law(multiplier * model.rate(followed)),
                                name=name)
        return
    rate = model.rate(link.coordinate)
    if not model.chart:
        model.generalized_force(link.coordinate, law(rate), name=name)
        return
    parent_support = (None, None) if link.parent is None else link.parent.support
    if not isinstance(joint, Revolute) or link.body is None or parent_support is None:
        raise ModelError(f"in an atlas, joint {what} acts as torques between two bodies: the "
                         "joint must be revolute or continuous, its child link and the link "
                         f"its parent is welded to must have mass; set the {what} to 0",
                         item=label)
    torque = law(rate) * (joint_frame.rotation * joint.unit_axis())
    model.torque(link.body, torque, name=name)
    if parent_support[0] is not None:
        model.torque(parent_support[0], -torque, name=f"{name}_reaction")


def _limit(model, q, joint, label: str) -> None:
    """The joint's range (none for a continuous joint, as in URDF) and its velocity and effort
    ratings."""
    limits = joint.limits
    ranged = not isinstance(joint, Continuous)
    lower, upper = (limits.lower, limits.upper) if ranged else (None, None)
    if any(value is not None for value in (lower, upper, limits.velocity, limits.effort)):
        model.limit(q, lower, upper, limits.velocity, name=label, effort=limits.effort)


def _initial(limits: Limits | None) -> float:
    """The suggested initial value: 0, or the nearest end of the range without 0."""
    if limits is None:
        return 0.0
    value = 0.0
    if limits.lower is not None and limits.upper is not None and limits.lower <= limits.upper:
        value = min(max(value, float(limits.lower)), float(limits.upper))
    return value


def _pin(model, link: Link, parent: Link | None, joint: Joint, joint_name: str) -> None:
    """The pins that hold the joint in the maximal model: points of the joint frame on the
    child body, pinned to the same points on the parent's supporting body (or the world)."""
    if isinstance(joint, Prismatic):
        # a sliding joint keeps the bodies' orientations equal, which pins between points
        # cannot say without also stopping the slide: the penalty model leaves it free
        link.unpinned = "a prismatic joint cannot be held by point pins"
        return
    if isinstance(joint, Free):
        link.unpinned = "a free joint holds nothing"
        return
    support = (None, Frame.identity()) if parent is None else parent.support
    if support is None:
        assert parent is not None  # the world supports a root link
        link.unpinned = (f"its parent '{parent.name}' is massless and moves, so no body "
                         "carries the joint's other half")
        return
    if isinstance(joint, Revolute):
        # two points of the axis: the child may turn about it and nothing else
        points = [[0, 0, 0], list(joint.unit_axis())]
    elif isinstance(joint, Ball):
        points = [[0, 0, 0]]  # the centre: the child may turn about it
    else:
        # three non-collinear points weld the child
        points = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
    parent_body, parent_offset = support
    assert link.body is not None and link.support is not None  # called for a link with a body
    child_offset = link.support[1]
    for index, local in enumerate(points):
        suffix = "abc"[index]
        in_parent = parent_offset.point(joint.origin.frame().point(local))
        child_point = link.body.point(list(child_offset.point(local)),
                                      name=f"{joint_name}_{suffix}")
        if parent_body is None:
            anchor = in_parent
        else:
            anchor = parent_body.point(list(in_parent), name=f"{joint_name}_{suffix}_parent")
        model.pin(child_point, anchor, name=f"{joint_name}_{suffix}")
        model.constraints[-1].joint = joint_name


def add_free_base(model, name: str, mass, inertia, com: Origin | None = None,
                  chart: str = "zyx") -> Link:
    """A link free to move: coordinates x, y, z (its origin) and three Euler angles of
    `chart` ('zyx': yaw, pitch, roll; 'yzx': heading, attitude, bank), singular where the
    middle angle is +-pi/2. Build one model per chart and add_chart the second for an atlas."""
    if chart not in EULER_CHARTS:
        raise ModelError(f"the chart is one of {', '.join(EULER_CHARTS)}, not {chart!r}",
                         item=f"link '{name}'")
    position = [model.coordinate(axis, f"origin of '{name}', {axis} (m)") for axis in "xyz"]
    rotation = sp.eye(3)
    angles = []
    for angle_name, axis, description in EULER_CHARTS[chart]:
        angles.append(model.coordinate(angle_name, f"'{name}': {description}"))
        rotation = rotation * rotation_about(axis, angles[-1])
    frame = Frame(rotation, position)
    link = Link(name, frame, None, None, coordinates=[*position, *angles],
                speeds=[model.rate(q) for q in [*position, *angles]], local=frame)
    model.links.append(link)
    link.body, link.inertial = _declare_body(model, name, frame, mass, inertia,
                                             com if com is not None else Origin(),
                                             f"link '{name}'")
    link.support = (link.body, link.inertial.inverse())
    return link
