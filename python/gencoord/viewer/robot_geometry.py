# SPDX-License-Identifier: BSD-3-Clause
"""What the viewer draws of a robot read from a URDF: each link's <visual> shapes (box,
cylinder, sphere, and STL or OBJ meshes whose files are found), posed rigidly with the body
the link belongs to, and where a link has none it can draw, a skeleton of capsules from its
joint to its children's joints (a sphere at the joint of a link without children).

A link's pose in its body's axes is `link.support` (joints.py): a link with mass is its own
body's, a massless link welded to one (a flange, a sensor) rides on that body, and a link
welded to the world is drawn in world axes. Each shape has a pose, a 4x4 matrix (row-major)
from its own axes to the body's axes about the body's point-mass mean, where the viewer puts
the body (scene.py); a cylinder's and a capsule's axis is their z axis, as in URDF.
"""

from __future__ import annotations

import base64
import math
import os
from array import array
from typing import Sequence

import sympy as sp

from gencoord.dsl.frames import Frame
from gencoord.viewer.mesh_files import read_triangles, resolve

Matrix = list[list[float]]  # 3x3
Pose = tuple[Matrix, list[float]]

# the skeleton's capsule radius, as a fraction of its length, and its bounds (m)
SKELETON_RADIUS = (0.1, 0.01, 0.04)


def package_path(extra: Sequence[str] = ()) -> list[str]:
    """Folders that hold URDF packages: `extra`, then ROS_PACKAGE_PATH's."""
    listed = os.environ.get("ROS_PACKAGE_PATH", "")
    return [*extra, *(folder for folder in listed.split(os.pathsep) if folder)]


def robot_visuals(model, numbers: dict, packages: Sequence[str] = ()
                  ) -> tuple[dict[str, list[dict]], list[dict]]:
    """The shapes of each body (by name) and those welded to the world, for the links read from
    a URDF (whose `geometry` is not None); empty for other models."""
    bodies: dict[str, list[dict]] = {}
    world: list[dict] = []
    for link in model.links:
        if link.geometry is None or link.support is None or model.dim != 3:
            continue
        body, in_support = link.support
        pose = _numeric(in_support, numbers)
        if pose is None:
            continue
        shapes = [shape for geometry in link.geometry if geometry.kind == "visual"
                  for shape in [_visual(geometry, pose, numbers, packages)] if shape]
        shapes = shapes or _skeleton(link, model, pose, numbers)
        if body is None:
            world.extend(_posed(shape, [0.0, 0.0, 0.0]) for shape in shapes)
        else:
            mean = _mean_offset(body, numbers)
            if mean is not None:
                bodies.setdefault(body.name, []).extend(_posed(shape, mean) for shape in shapes)
    return bodies, world


def _number(expr, numbers: dict) -> float | None:
    value = sp.sympify(expr).xreplace(numbers)
    return float(value) if value.is_number else None


def _numeric(frame: Frame, numbers: dict) -> Pose | None:
    rotation = [[_number(frame.rotation[i, j], numbers) for j in range(3)] for i in range(3)]
    origin = [_number(frame.origin[i], numbers) for i in range(3)]
    if any(v is None for row in rotation for v in row) or None in origin:
        return None
    return rotation, origin  # type: ignore[return-value]  # no None left


def _compose(a: Pose, b: Pose) -> Pose:
    (ra, oa), (rb, ob) = a, b
    rotation = [[sum(ra[i][k] * rb[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    return rotation, [oa[i] + sum(ra[i][k] * ob[k] for k in range(3)) for i in range(3)]


def _mean_offset(body, numbers: dict) -> list[float] | None:
    offsets = [[_number(r[i], numbers) for i in range(3)] for r in body.offsets]
    if not offsets or any(None in r for r in offsets):
        return None
    return [sum(r[i] for r in offsets) / len(offsets) for i in range(3)]  # type: ignore


def _posed(shape: dict, mean: list[float]) -> dict:
    """The shape with its pose as a row-major 4x4 about the body's point-mass mean."""
    rotation, origin = shape.pop("at")
    shape["pose"] = [round(v, 12) for row, o, m in zip(rotation, origin, mean)
                     for v in (*row, o - m)] + [0.0, 0.0, 0.0, 1.0]
    return shape


def _numbers(text: str | None, count: int) -> list[float] | None:
    try:
        values = [float(word) for word in (text or "").split()]
    except ValueError:
        return None
    return values if len(values) == count and all(map(math.isfinite, values)) else None


def _visual(geometry, pose: Pose, numbers: dict, packages: Sequence[str]) -> dict | None:
    """A <visual>'s shape and pose, or None where it cannot be drawn (a missing mesh)."""
    at = _numeric(geometry.origin.frame(), numbers)
    if at is None:
        return None
    at = _compose(pose, at)
    attributes = geometry.attributes
    if geometry.shape == "box":
        size = _numbers(attributes.get("size"), 3)
        return {"kind": "box", "size": size, "at": at} if size else None
    if geometry.shape in ("cylinder", "sphere"):
        radius = _numbers(attributes.get("radius"), 1)
        length = _numbers(attributes.get("length"), 1) if geometry.shape == "cylinder" else [0]
        if not radius or not length:
            return None
        shape = {"kind": geometry.shape, "radius": radius[0], "at": at}
        return shape | ({"length": length[0]} if geometry.shape == "cylinder" else {})
    if geometry.shape == "mesh" and geometry.source:
        path = resolve(attributes.get("filename", ""), geometry.source, packages)
        corners = read_triangles(path) if path else None
        scale = _numbers(attributes.get("scale", "1 1 1"), 3)
        if not corners or not scale:
            return None
        scaled = array("f", (c * scale[k % 3] for k, c in enumerate(corners)))
        return {"kind": "mesh", "triangles": base64.b64encode(scaled.tobytes()).decode("ascii"),
                "at": at}
    return None


def _skeleton(link, model, pose: Pose, numbers: dict) -> list[dict]:
    """Capsules from the link's joint to each child's joint, in the link's support axes; a
    sphere at its joint where it has no child away from it."""
    start = pose[1]
    shapes = []
    for child in (other for other in model.links if other.parent is link):
        joint = _numeric(child.joint.origin.frame(), numbers) if child.joint else None
        if joint is None:
            continue
        end = _compose(pose, joint)[1]
        axis = [e - s for e, s in zip(end, start)]
        length = math.sqrt(sum(a * a for a in axis))
        if length < 1e-9:
            continue
        fraction, smallest, largest = SKELETON_RADIUS
        radius = min(max(fraction * length, smallest), largest)
        middle = [(s + e) / 2 for s, e in zip(start, end)]
        shapes.append({"kind": "capsule", "radius": radius, "length": length,
                       "at": (_frame_along([a / length for a in axis]), middle)})
    if not shapes:
        identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
        shapes.append({"kind": "sphere", "radius": 2 * SKELETON_RADIUS[1],
                       "at": (identity, list(start))})
    return shapes


def _frame_along(z: list[float]) -> Matrix:
    """A rotation whose third column is the unit vector z."""
    helper = [1.0, 0.0, 0.0] if abs(z[0]) < 0.9 else [0.0, 1.0, 0.0]
    x = [helper[1] * z[2] - helper[2] * z[1], helper[2] * z[0] - helper[0] * z[2],
         helper[0] * z[1] - helper[1] * z[0]]
    norm = math.sqrt(sum(c * c for c in x))
    x = [c / norm for c in x]
    y = [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]]
    return [[x[i], y[i], z[i]] for i in range(3)]
