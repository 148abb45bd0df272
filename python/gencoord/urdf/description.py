# SPDX-License-Identifier: BSD-3-Clause
"""A URDF file read into links and joints, checked as a tree; nothing is declared on a model.

Read: each link's <inertial> (origin, mass, inertia), visual and collision elements (kept as
metadata), each joint's type, parent, child, <origin>, <axis>, <limit> and <dynamics>. Every
refusal names the file, the element's line and the link or joint.
"""

from __future__ import annotations

import textwrap
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

import sympy as sp

from gencoord.dsl.bodies import inertia_problem
from gencoord.errors import ModelError
from gencoord.dsl.joints import (Continuous, Fixed, Free, Joint, Limits, Origin, Prismatic,
                                 Revolute)
from gencoord.urdf.point_masses import fold_point_masses, is_zero_tensor
from gencoord.urdf.xml_lines import XmlFile

JOINT_TYPES = {"revolute": Revolute, "continuous": Continuous, "prismatic": Prismatic,
               "fixed": Fixed}
FLOATING = "floating"


@dataclass
class Inertial:
    mass: float
    inertia: sp.Matrix
    origin: Origin


@dataclass
class Geometry:
    """A visual or collision element: its kind, origin and shape (the tag and attributes of
    the <geometry> child: box size, cylinder radius and length, mesh filename ...)."""
    kind: str
    name: str | None
    origin: Origin
    shape: str | None
    attributes: dict
    line: int | None
    source: str | None = None  # the URDF's path, which a mesh's file name is relative to


@dataclass
class LinkDescription:
    name: str
    line: int | None
    inertial: Inertial | None = None
    geometry: list[Geometry] = field(default_factory=list)


@dataclass
class MimicDescription:
    """A <mimic>: the joint follows `joint` as multiplier * q + offset."""
    joint: str
    multiplier: float
    offset: float
    line: int | None


@dataclass
class JointDescription:
    name: str
    line: int | None
    kind: str
    parent: str
    child: str
    joint: Joint
    mimic: MimicDescription | None = None


@dataclass
class RobotDescription:
    name: str
    path: str
    links: dict[str, LinkDescription]
    joints: dict[str, JointDescription]  # by the child link's name
    root: str
    comments: list[str]
    ignored: list[str] = field(default_factory=list)  # what the file holds that is not read

    def order(self) -> list[str]:
        """The links depth first from the root, children in the file's order: a leg's joints
        come together."""
        children: dict[str, list[str]] = {}
        for joint in self.joints.values():
            children.setdefault(joint.parent, []).append(joint.child)
        order, stack = [], [self.root]
        while stack:
            name = stack.pop()
            order.append(name)
            stack += reversed(children.get(name, []))
        return order


def _origin(xml: XmlFile, parent: ET.Element, item: str) -> Origin:
    element = parent.find("origin")
    if element is None:
        return Origin()
    return Origin(xml.numbers(element, "xyz", 3, (0, 0, 0), item),
                  xml.numbers(element, "rpy", 3, (0, 0, 0), item))


def _check_inertia(xml: XmlFile, element: ET.Element, mass: float, matrix: sp.Matrix,
                   item: str) -> None:
    """Refuses an inertia tensor no rigid body has (bodies.inertia_problem); a zero one is a
    point mass (point_masses.py)."""
    if is_zero_tensor(matrix):
        return
    problem = inertia_problem(sp.Float(mass), matrix)
    if problem:
        raise xml.error(problem, element, item)


def _inertial(xml: XmlFile, link: ET.Element, item: str) -> Inertial | None:
    inertial = link.find("inertial")
    if inertial is None:
        return None
    mass, inertia = inertial.find("mass"), inertial.find("inertia")
    for child, what in ((mass, "<mass value=...>"), (inertia, "<inertia ixx=... izz=...>")):
        if child is None:
            raise xml.error(f"<inertial> needs {what}; remove <inertial> for a massless link",
                            inertial, item)
    assert mass is not None and inertia is not None  # refused just above
    value = xml.number(mass, "value", item=item)
    if value <= 0:
        raise xml.error(f"the mass is {value:g}; give a positive mass, or remove <inertial> "
                        "for a massless link", mass, item)
    m = {key: xml.number(inertia, key, 0.0 if key[1] != key[2] else None, item)
         for key in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
    matrix = sp.Matrix([[m["ixx"], m["ixy"], m["ixz"]], [m["ixy"], m["iyy"], m["iyz"]],
                        [m["ixz"], m["iyz"], m["izz"]]])
    _check_inertia(xml, inertia, value, matrix, item)
    return Inertial(value, matrix, _origin(xml, inertial, item))


def _geometry(xml: XmlFile, link: ET.Element, item: str) -> list[Geometry]:
    found = []
    for kind in ("visual", "collision"):
        for element in link.findall(kind):
            geometry = element.find("geometry")
            shapes = [] if geometry is None else list(geometry)
            shape = shapes[0] if shapes else None
            found.append(Geometry(kind, element.get("name"), _origin(xml, element, item),
                                  None if shape is None else shape.tag,
                                  {} if shape is None else dict(shape.attrib),
                                  xml.line(element), xml.path))
    return found


def _limits(xml: XmlFile, joint: ET.Element, item: str) -> Limits | None:
    limit = joint.find("limit")
    if limit is None:
        return None
    values = {key: (xml.number(limit, key, item=item) if limit.get(key) is not None else None)
              for key in ("lower", "upper", "effort", "velocity")}
    if joint.get("type") != "continuous":
        # URDF's defaults for a ranged joint
        values = {key: 0.0 if value is None and key in ("lower", "upper") else value
                  for key, value in values.items()}
    lower, upper = values["lower"], values["upper"]
    if lower is not None and upper is not None and lower > upper:
        raise xml.error(f"<limit lower=\"{limit.get('lower')}\" upper=\"{limit.get('upper')}\">"
                        " is reversed: lower must not exceed upper", limit, item)
    return Limits(**values)


def _name(xml: XmlFile, element: ET.Element) -> str:
    name = element.get("name")
    if not name:
        raise xml.error(f"a <{element.tag}> needs a name attribute", element)
    return name


def _link_of(xml: XmlFile, joint: ET.Element, which: str, item: str) -> str:
    element = joint.find(which)
    link = None if element is None else element.get("link")
    if not link:
        raise xml.error(f"<joint> needs <{which} link=\"...\">", joint, item)
    return link


def _joint(xml: XmlFile, element: ET.Element) -> JointDescription:
    name = _name(xml, element)
    item = f"joint '{name}'"
    kind = element.get("type")
    parent, child = _link_of(xml, element, "parent", item), _link_of(xml, element, "child", item)
    origin = _origin(xml, element, item)
    if kind == "planar":
        raise xml.error("planar joints are not supported; model one as two prismatic joints "
                        "and a revolute joint through massless links", element, item)
    if kind == FLOATING:  # its origin is the base's initial pose
        return JointDescription(name, xml.line(element), kind, parent, child,
                                Free(origin, name=name))
    if kind not in JOINT_TYPES:
        raise xml.error(f"type {kind!r} is not a joint type: use one of "
                        f"{', '.join([*JOINT_TYPES, FLOATING])}", element, item)
    if kind == "fixed":
        joint = Fixed(origin, name=name)
    else:
        axis_element = element.find("axis")
        axis = ([1.0, 0.0, 0.0] if axis_element is None
                else xml.numbers(axis_element, "xyz", 3, (1.0, 0.0, 0.0), item))
        if all(v == 0 for v in axis):
            raise xml.error("the axis is zero; give the direction the joint moves about or "
                            "along, e.g. <axis xyz=\"0 0 1\"/>",
                            element if axis_element is None else axis_element, item)
        dynamics = element.find("dynamics")
        damping, friction = (0.0, 0.0) if dynamics is None else (
            _resistance(xml, dynamics, "damping", item),
            _resistance(xml, dynamics, "friction", item))
        joint = JOINT_TYPES[kind](axis, origin, _limits(xml, element, item), damping,
                                  name=name, friction=friction)
    return JointDescription(name, xml.line(element), kind, parent, child, joint,
                            _mimic(xml, element, kind, item))


def _resistance(xml: XmlFile, dynamics: ET.Element, what: str, item: str) -> float:
    """<dynamics damping> or <dynamics friction>: a non-negative number, 0 when absent."""
    value = xml.number(dynamics, what, 0.0, item)
    if value < 0:
        raise xml.error(f"the {what} is {value:g}; give a non-negative {what}", dynamics, item)
    return value


def _check_mimic(xml: XmlFile, joint: JointDescription, joints: dict, elements: dict) -> None:
    """Refuses a <mimic> of a joint that is not in the file, has no coordinate to follow, or
    follows another."""
    if joint.mimic is None:
        return
    mimic = elements[joint.name].find("mimic")
    followed = joints.get(joint.mimic.joint)
    problem = None
    if followed is None:
        problem = f"it follows joint '{joint.mimic.joint}', which is not a <joint> of this file"
    elif followed is joint:
        problem = "it follows itself"
    elif followed.kind not in ("revolute", "continuous", "prismatic"):
        problem = (f"it follows joint '{followed.name}', a {followed.kind} joint, which has no "
                   "coordinate to follow")
    elif followed.mimic is not None:
        problem = (f"it follows joint '{followed.name}', which follows '{followed.mimic.joint}'; "
                   "follow that joint instead")
    if problem:
        raise xml.error(problem, mimic, f"joint '{joint.name}'")


def _mimic(xml: XmlFile, element: ET.Element, kind: str, item: str) -> MimicDescription | None:
    mimic = element.find("mimic")
    if mimic is None:
        return None
    if kind not in ("revolute", "continuous", "prismatic"):
        raise xml.error(f"a {kind} joint cannot mimic another; only revolute, continuous and "
                        "prismatic joints can", mimic, item)
    followed = mimic.get("joint")
    if not followed:
        raise xml.error("<mimic> needs joint=\"...\", the joint it follows", mimic, item)
    return MimicDescription(followed, xml.number(mimic, "multiplier", 1.0, item),
                            xml.number(mimic, "offset", 0.0, item), xml.line(mimic))


def _check_tree(xml: XmlFile, links: dict, joints: list[JointDescription],
                elements: dict) -> tuple[dict, str]:
    """The joints by child link, and the root; refuses unknown links, two parents, cycles
    and several roots or none."""
    by_child: dict[str, JointDescription] = {}
    for joint in joints:
        for end, which in ((joint.parent, "parent"), (joint.child, "child")):
            if end not in links:
                raise xml.error(f"its {which} link '{end}' is not a <link> of this file",
                                elements[joint.name], f"joint '{joint.name}'")
        if joint.child in by_child:
            raise xml.error(f"link '{joint.child}' has two parents: joint "
                            f"'{by_child[joint.child].name}' already joins it to "
                            f"'{by_child[joint.child].parent}'; a URDF is a tree",
                            elements[joint.name], f"joint '{joint.name}'")
        by_child[joint.child] = joint
    roots = [name for name in links if name not in by_child]
    if len(roots) > 1:
        raise ModelError(f"the tree has {len(roots)} roots ({', '.join(roots)}): every link "
                         "but one needs a joint that makes it a child", item=f"link '{roots[1]}'",
                         filename=xml.path, line=links[roots[1]].line)
    for name in links:
        seen, link = [], name
        while link in by_child and link not in seen:
            seen.append(link)
            link = by_child[link].parent
        if link in seen:
            cycle = seen[seen.index(link):]
            joint = by_child[cycle[0]]
            raise xml.error(f"the joints form a cycle through links {', '.join(cycle)}; a "
                            "URDF is a tree", elements[joint.name], f"joint '{joint.name}'")
    return by_child, roots[0]


def read_urdf(path: str) -> RobotDescription:
    """Parses and checks the URDF at `path`."""
    xml = XmlFile(path)
    root = xml.root
    if root.tag != "robot":
        raise xml.error(f"the root element is <{root.tag}>, not <robot>: is this a URDF?", root)
    for element in root.iter():
        if element.tag.startswith("xacro:"):
            raise xml.error("this is a xacro file; expand it first (xacro robot.urdf.xacro > "
                            "robot.urdf)", element)
    links: dict[str, LinkDescription] = {}
    for element in root.findall("link"):
        name = _name(xml, element)
        item = f"link '{name}'"
        if name in links:
            raise xml.error(f"a second link is called '{name}'; link names are unique",
                            element, item)
        links[name] = LinkDescription(name, xml.line(element), _inertial(xml, element, item),
                                      _geometry(xml, element, item))
    if not links:
        raise xml.error("the robot has no <link>", root)
    joints, elements = [], {}
    for element in root.findall("joint"):
        joint = _joint(xml, element)
        if joint.name in elements:
            raise xml.error(f"a second joint is called '{joint.name}'; joint names are unique",
                            element, f"joint '{joint.name}'")
        joints.append(joint)
        elements[joint.name] = element
    by_child, root_link = _check_tree(xml, links, joints, elements)
    for joint in joints:
        if joint.kind == FLOATING and joint.parent != root_link:
            raise xml.error("a floating joint joins the root link (the world) to the base, "
                            f"but its parent '{joint.parent}' is not the root; make the root "
                            "its parent",
                            elements[joint.name], f"joint '{joint.name}'")
        _check_mimic(xml, joint, {j.name: j for j in joints}, elements)
    robot = RobotDescription(root.get("name") or "robot", path, links, by_child, root_link,
                             [textwrap.dedent(c.strip("\n")).strip()
                              for c in xml.leading_comments], _ignored(root))
    fold_point_masses(robot)
    return robot


# elements a URDF may hold that the dynamics does not read, and what each is
_NOT_READ = {"transmission": "actuator transmissions", "gazebo": "Gazebo extensions",
             "material": "materials", "safety_controller": "safety controllers",
             "calibration": "joint calibrations"}


def _ignored(root) -> list[str]:
    """One line per kind of element the model leaves out: the <dynamics> of fixed and floating
    joints (nothing moves for them to resist), and the elements of _NOT_READ, each with its
    count."""
    lines = []
    unread = [joint.get("name") or "?" for joint in root.findall("joint")
              if joint.get("type") in ("fixed", FLOATING)
              for dynamics in joint.findall("dynamics")
              if any(dynamics.get(what, "0").strip() not in ("0", "0.0", "")
                     for what in ("damping", "friction"))]
    if unread:
        shown = ", ".join(unread[:3]) + (", ..." if len(unread) > 3 else "")
        lines.append(f"<dynamics> of {len(unread)} fixed or floating joint(s) ({shown}): "
                     "such a joint has no coordinate to damp")
    for tag, what in _NOT_READ.items():
        count = sum(1 for _ in root.iter(tag))
        if count:
            lines.append(f"{count} <{tag}> element(s): {what}")
    return lines
