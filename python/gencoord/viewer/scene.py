# SPDX-License-Identifier: BSD-3-Clause
"""What a picture of a model needs, as JSON: its particles, fixed points, bodies with an
inertia-equivalent shape (a rolling wheel: its disk; a robot's link: its URDF visuals or a
skeleton, robot_geometry.py), the rods, springs, dampers, pins and planes it declares (the
ground plane under rolling wheels), and the direction against gravity.

Positions are not in the scene: a trajectory (the simulate program's CSV) holds those of the
particles and fixed points, row by row. Every other point is given as an affine combination
of them, an "anchor": a list of [column, weight] pairs, where a column is a particle's name or
"fixed:<name>" (the CSV's prefix of fixed points). A body's point masses (bodies.py) are not
drawn as particles: the viewer recovers the body's pose from them (x_k = p + R r_k with the
offsets r_k listed here) and draws the body's shape.

Geometry is evaluated at parameter values: the defaults when generation writes the scene
beside the header, the values of a run when the viewer draws one.
"""

from __future__ import annotations

import json
from typing import Mapping, Sequence

import mpmath
import sympy as sp

from gencoord.checks.conservative import conserves_energy
from gencoord.dsl.model import Model

from gencoord.dsl.items import (Body, BodyParticle, BodyPoint, FixedPoint, Pin, Plane, Point, Rod,
                                Wheel)
from gencoord.viewer.robot_geometry import package_path, robot_visuals

FORMAT = "gencoord-scene 1"
FIXED_PREFIX = "fixed:"  # the CSV's columns of fixed points (runtime csv_writer.hpp)
# what rolling wheels roll on (rolling_wheel): the plane z = 0
GROUND = {"name": "ground", "particle": None, "normal": [0.0, 0.0, 1.0], "offset": 0.0}
# a wheel's width as a fraction of its radius, for its picture
WHEEL_WIDTH = 0.15
# a body whose inertia vanishes about some axis (a thin rod) still gets this fraction of its
# largest semi-axis, so that it stays visible
MIN_THICKNESS = 0.05


def scene(model: Model, name: str, values: Mapping[str, float] | None = None,
          packages: Sequence[str] = ()) -> dict:
    """The scene of `model` as a JSON-ready dict, with parameters at `values` (by name) and
    at their defaults otherwise; a URDF's mesh files found through `packages` (folders that
    hold package:// packages)."""
    given = dict(values or {})
    numbers = {p.symbol: sp.Float(float(given.get(p.name, p.default)))
               for p in model.parameters}
    body_particles = {p.name for body in model.bodies for p in body.particles}
    wheels = {wheel.body.name: wheel for wheel in model.wheels}
    visuals, world_visuals = robot_visuals(model, numbers, packages)
    bodies = [_body(body, numbers, wheels.get(body.name)) for body in model.bodies]
    for body in bodies:
        if body["name"] in visuals:  # a robot's link: drawn as its URDF visuals or skeleton
            body["visuals"] = visuals[body["name"]]
    # a robot's joints are drawn by its links: not the maximal model's pins on them (two per
    # hinge, the second a metre along its axis)
    on_links = {p.name for body in model.bodies if body.name in visuals for p in body.particles}
    links = [link for link in _links(model, numbers, body_particles) if link and not (
        link["kind"] == "pin" and {c for end in ("a", "b") for c, _ in link[end]} <= on_links)]
    return {
        "format": FORMAT,
        "name": name,
        "dim": model.dim,
        "up": _up(model, numbers),
        # whether E - E0 of a run is an error (a conservative model) or the energy's change
        "conserves_energy": conserves_energy(model),
        "particles": [{"name": p.name, "mass": _number(p.mass, numbers)}
                      for p in model.particles if not isinstance(p, BodyParticle)],
        "fixed_points": [p.name for p in model.fixed_points],
        "bodies": bodies,
        "links": links,
        "planes": ([_plane(plane, numbers) for plane in model.constraints
                    if isinstance(plane, Plane)] + ([GROUND] if model.wheels else [])),
        # pins to a position that never moves: where they hold their point (with the body
        # whose point it is, drawn joined to its centre)
        "pivots": [{"name": pin.name, "position": _vector(pin.anchor, numbers),
                    "body": pin.particle.body.name if isinstance(pin.particle, BodyPoint)
                    else None}
                   for pin in model.constraints if isinstance(pin, Pin)
                   and not isinstance(pin.anchor, Point) and _vector(pin.anchor, numbers)
                   and not (isinstance(pin.particle, BodyPoint)
                            and pin.particle.body.name in visuals)],
        **({"world_visuals": world_visuals} if world_visuals else {}),
    }


def scene_json(model: Model, name: str, values: Mapping[str, float] | None = None) -> str:
    """The scene as JSON text, byte for byte the same for the same model and values."""
    return json.dumps(scene(model, name, values, package_path()), indent=1) + "\n"


def _rounded(value: float) -> float:
    """12 significant digits: far finer than a picture needs, and the same whatever the last
    bits of SymPy's or mpmath's arithmetic."""
    return float(f"{value:.12g}") + 0.0  # + 0.0: no -0.0


def _number(expr, numbers: dict) -> float | None:
    """The value of `expr` at the parameter values; None where it depends on q or t."""
    value = sp.sympify(expr).xreplace(numbers)
    return _rounded(float(value)) if value.is_number else None


def _vector(vector: sp.Matrix, numbers: dict) -> list[float] | None:
    values = [_number(component, numbers) for component in vector]
    known = [value for value in values if value is not None]
    return known if len(known) == len(values) else None


def anchor(point: Point, numbers: dict) -> list | None:
    """The point as [[column, weight], ...] over the CSV's points (module docstring)."""
    if isinstance(point, FixedPoint):
        return [[FIXED_PREFIX + point.name, 1.0]]
    if isinstance(point, BodyPoint):
        weights = [_number(w, numbers) for w in point.weights]
        if None in weights:
            return None
        return [[p.name, w] for p, w in zip(point.body.particles, weights)]
    return [[point.name, 1.0]]


def _up(model: Model, numbers: dict) -> list[float]:
    """The unit vector against gravity; without gravity, y in 2D and z in 3D."""
    total = sp.zeros(model.dim, 1)
    for gravity in model.gravities:
        total += gravity.acceleration
    values = _vector(total, numbers)
    length = sum(v * v for v in values) ** 0.5 if values else 0.0
    if values is None or not length:
        return [0.0, 1.0] if model.dim == 2 else [0.0, 0.0, 1.0]
    return [_rounded(-v / length) for v in values]


def _links(model: Model, numbers: dict, body_particles: set[str]):
    for spring in model.springs:
        yield _link("spring", spring.name, spring.a, spring.b, numbers,
                    rest_length=_number(spring.rest_length, numbers))
    for damper in model.dampers:
        yield _link("damper", damper.name, damper.a, damper.b, numbers)
    for constraint in model.constraints:
        if isinstance(constraint, Rod):
            if {constraint.a.name, constraint.b.name} <= body_particles:
                continue  # a body's own rods keep its point masses rigid: not drawn
            yield _link("rod", constraint.name, constraint.a, constraint.b, numbers,
                        length=_number(constraint.length, numbers))
        elif isinstance(constraint, Pin) and isinstance(constraint.anchor, Point):
            yield _link("pin", constraint.name, constraint.particle, constraint.anchor, numbers)


def _link(kind: str, name: str, a: Point, b: Point, numbers: dict, **extra) -> dict | None:
    ends = anchor(a, numbers), anchor(b, numbers)
    if None in ends:
        return None  # weights that move with q: nothing the viewer could draw
    return {"kind": kind, "name": name, "a": ends[0], "b": ends[1], **extra}


def _plane(plane: Plane, numbers: dict) -> dict:
    return {"name": plane.name, "particle": plane.particle.name,
            "normal": _vector(plane.normal, numbers), "offset": _number(plane.offset, numbers)}


def _body(body: Body, numbers: dict, wheel: Wheel | None) -> dict:
    mass = _number(body.mass, numbers)
    offsets = [_vector(r, numbers) for r in body.offsets]
    shape = _wheel(wheel, offsets, numbers) if wheel else None
    return {"name": body.name, "mass": mass, "points": [p.name for p in body.particles],
            "offsets": offsets, "shape": shape or _ellipsoid(body, mass, numbers)}


def _wheel(wheel: Wheel, offsets: list, numbers: dict) -> dict | None:
    """A rolling wheel's disk: its radius, its unit axle in body axes, and its centre in body
    axes from the body's point masses' mean (where the viewer puts the body's origin)."""
    radius, axle, center = (_number(wheel.radius, numbers), _vector(wheel.axle, numbers),
                            _vector(wheel.center, numbers))
    if radius is None or axle is None or center is None or None in offsets:
        return None
    length = sum(a * a for a in axle) ** 0.5
    mean = [sum(r[i] for r in offsets) / len(offsets) for i in range(3)]
    return {"kind": "wheel", "radius": radius, "width": _rounded(WHEEL_WIDTH * radius),
            "axle": [_rounded(a / length) for a in axle],
            "center": [_rounded(c - m) for c, m in zip(center, mean)]}


def _ellipsoid(body: Body, mass: float | None, numbers: dict) -> dict | None:
    """The solid ellipsoid (in 2D the disk) with the body's mass and inertia: semi-axes
    a_i = sqrt(5 s_i / m) along the eigenvectors of the second moment S (disk radius
    sqrt(2 I / m)), in body axes."""
    assert body.second_moment is not None  # set with the point masses (add_point_masses)
    moment = body.second_moment.xreplace(numbers)
    if not mass or not all(value.is_number for value in moment):
        return None
    if body.frame.dim == 2:
        radius = (4.0 * float(moment[0, 0]) / mass) ** 0.5
        return {"kind": "disk", "radius": radius}
    if all(moment[i, j] == 0 for i in range(3) for j in range(3) if i != j):
        # principal already; eigsy would pick any basis of a repeated eigenvalue's plane
        values, vectors = [moment[k, k] for k in range(3)], mpmath.eye(3)
    else:
        values, vectors = mpmath.eigsy(mpmath.matrix([[float(moment[i, j]) for j in range(3)]
                                                      for i in range(3)]))
    semi_axes = [(5.0 * max(float(values[k]), 0.0) / mass) ** 0.5 for k in range(3)]
    thinnest = MIN_THICKNESS * max(semi_axes)
    axes = []  # each principal axis, its largest component positive: one answer of the two
    for k in range(3):
        column = [float(vectors[i, k]) for i in range(3)]
        sign = 1.0 if max(column, key=abs) > 0 else -1.0
        axes.append([_rounded(sign * c) for c in column])
    return {"kind": "ellipsoid",
            "semi_axes": [_rounded(max(a, thinnest)) for a in semi_axes],
            "axes": axes}  # rows: the principal axes in body axes
