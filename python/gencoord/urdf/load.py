# SPDX-License-Identifier: BSD-3-Clause
"""URDF import: a robot description's links and joints added to a model as a joint tree.

In a model file, to add forces or script joints on top:

    from gencoord import Model, load_urdf
    model = Model(dim=3)
    links = load_urdf(model, "arm.urdf")        # relative to the model file
    elbow = links.coordinates["elbow"]          # a joint's coordinate, by the joint's name
    model.joint_spring(elbow, 50.0)

or directly, `./generate arm.urdf`: the loader builds the model with `urdf_model`. Numbers
stay literals in the expressions; gravity is -g along z, with the parameter g = 9.81.
"""

from __future__ import annotations

import contextlib
import os

from gencoord.errors import ModelError
from gencoord.dsl.joints import (Fixed, Free, Joint, Link, Mimic, Origin, Prismatic, Revolute,
                                 add_free_base, add_link)
from gencoord.dsl.model import Model
from gencoord.dsl.items import model_file_frame
from gencoord.urdf.description import FLOATING, RobotDescription, read_urdf


class UrdfTree(dict):
    """The links by name; `coordinates` maps each moving joint's name (and a free base's
    coordinate names) to its coordinate symbol; `robot` is the file's description."""

    def __init__(self, robot: RobotDescription):
        super().__init__()
        self.robot = robot
        self.coordinates: dict = {}


def _calling_file_directory() -> str:
    """The directory of the model file that called in (its __file__), else the working one."""
    frame = model_file_frame()
    caller = frame.f_globals.get("__file__") if frame is not None else None
    return os.path.dirname(os.path.abspath(caller)) if caller else os.getcwd()


@contextlib.contextmanager
def _at(model: Model, path: str, line: int | None, stamp: bool):
    """Errors of the declarations inside point at the URDF's line; with `stamp`, so do the
    items declared (for the checks that run later)."""
    before = {key: len(value) for key, value in vars(model).items() if isinstance(value, list)}
    try:
        yield
    except ModelError as error:
        raise ModelError(error.message, item=error.item, filename=path, line=line) from None
    if stamp:
        for key, value in vars(model).items():
            if isinstance(value, list):
                for item in value[before.get(key, 0):]:
                    if hasattr(item, "line"):
                        item.line = line


def _inertial_arguments(robot: RobotDescription, name: str) -> dict:
    inertial = robot.links[name].inertial
    if inertial is None:
        return {}
    return {"mass": inertial.mass, "inertia": inertial.inertia, "com": inertial.origin}


def _free_base(model: Model, robot: RobotDescription, name: str, joint: Joint,
               chart: str | None) -> Link:
    """The base link, free: a unit quaternion and the body twist (a Free joint whose origin is
    the initial pose), or with `chart` (or in a model that is a chart) three Euler angles. A
    free joint's base may be massless (a frame link welded to a massive trunk, as robots ship
    it); the rank check refuses it when no mass follows it rigidly."""
    arguments = _inertial_arguments(robot, name)
    if chart or model.chart:
        if not arguments:
            raise ModelError("a free-floating base in Euler angles needs an <inertial> with its "
                             "mass (or load the URDF without a chart: a free joint)",
                             item=f"link '{name}'", filename=robot.path,
                             line=robot.links[name].line)
        return add_free_base(model, name, chart=chart or model.chart or "zyx", **arguments)
    return add_link(model, name, None, joint, **arguments)


def _mimic(robot: RobotDescription, joint, links: UrdfTree) -> Mimic:
    """The Mimic of a joint whose <mimic> follows a joint loaded before it."""
    mimic = joint.mimic
    followed = links.coordinates.get(mimic.joint)
    if followed is None:
        raise ModelError(f"it follows joint '{mimic.joint}', which comes after it in the tree "
                         "(depth first from the root, children in the file's order); put the "
                         "followed joint's branch first", item=f"joint '{joint.name}'",
                         filename=robot.path, line=mimic.line)
    return Mimic(followed, mimic.multiplier, mimic.offset)


def add_robot(model: Model, robot: RobotDescription, gravity: bool = True,
              free_base: bool = False, chart: str | None = None,
              stamp: bool = False) -> UrdfTree:
    """Adds a read URDF's links to `model` (see load_urdf); `stamp` makes the declared items'
    lines the URDF's (when the model has no file of its own)."""
    links = UrdfTree(robot)
    model.ignored.extend(robot.ignored)
    for name in robot.order():
        joint = robot.joints.get(name)
        line = robot.links[name].line if joint is None else joint.line
        with _at(model, robot.path, line, stamp):
            if joint is None and free_base:
                link = _free_base(model, robot, name, Free(Origin()), chart)
            elif joint is not None and joint.kind == FLOATING:
                link = _free_base(model, robot, name, joint.joint, chart)
            elif joint is None:
                # the root is the world, or welded to it: add_link gives it no body
                link = add_link(model, name, None, Fixed(Origin()))
            else:
                if joint.mimic is not None:
                    assert isinstance(joint.joint, (Revolute, Prismatic))  # _check_mimic
                    joint.joint.mimic = _mimic(robot, joint, links)
                link = add_link(model, name, links[joint.parent], joint.joint,
                                **_inertial_arguments(robot, name))
        link.geometry = robot.links[name].geometry
        links[name] = link
        if link.coordinate is not None:
            assert joint is not None  # a coordinate of its own: the link has a moving joint
            links.coordinates[joint.name] = link.coordinate
        elif link.coordinates:  # a free base
            links.coordinates.update((str(q), q) for q in link.coordinates)
    if gravity:
        with _at(model, robot.path, robot.links[robot.root].line, stamp):
            g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
            model.gravity([0, 0, -g])
    return links


def load_urdf(model: Model, path: str, gravity: bool = True, free_base: bool = False,
              chart: str | None = None) -> UrdfTree:
    """Adds the URDF file's robot to `model` (3D); returns its links by name.

    `path` is relative to the calling model file. The root link is welded to the world
    unless `free_base` is true or a floating joint joins it to the base: the base then moves
    freely, its orientation a unit quaternion (the floating joint's origin is its initial
    pose), or with `chart` ('zyx' or 'yzx', or the model's chart name) three Euler angles.
    With `gravity`, -g along z and the parameter g (9.81 m/s^2).
    """
    if not os.path.isabs(path):
        path = os.path.join(_calling_file_directory(), path)
    return add_robot(model, read_urdf(path), gravity, free_base, chart)


def _description(robot: RobotDescription) -> str:
    moving = sum(1 for j in robot.joints.values() if j.kind != "fixed")
    summary = (f"Robot '{robot.name}' from {os.path.basename(robot.path)}: "
               f"{len(robot.links)} links, {moving} moving joints.")
    return "\n\n".join([summary, *robot.comments])


def urdf_model(path: str) -> Model:
    """The model of a URDF file (a floating joint's base is a free joint: a unit quaternion
    and the body twist; a model file that loads the URDF into a chart gets Euler angles)."""
    robot = read_urdf(path)
    model = Model(dim=3, description=_description(robot))
    add_robot(model, robot, stamp=True)
    model.line = robot.links[robot.root].line
    if not model.coordinates:  # validate's advice (model.coordinate) is for model files
        raise ModelError(f"no joint of the robot moves (it has {len(robot.joints)} joints, "
                         "none of them revolute, continuous, prismatic or floating); there is "
                         "nothing to simulate", filename=path, line=model.line)
    return model
