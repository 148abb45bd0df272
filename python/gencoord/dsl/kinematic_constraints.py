# SPDX-License-Identifier: BSD-3-Clause
"""Kinematic constraints that the coordinates do not remove.

A model is a parameterization x = X(q, t); a closed loop (a four-bar, a parallel robot) or a
rolling contact (a disk, a bicycle) adds conditions that no choice of tree coordinates
satisfies. They are declared here and kept as equations beside the dynamics:

- holonomic, C(q, t) = 0: `holonomic_constraint`, or `close_loop` (two points coincide);
- nonholonomic, A(q, t) v + b(q, t) = 0, linear in the speeds: `velocity_constraint`, or
  `rolling_wheel` (a wheel rolling without slipping on the ground, rolling.py).

The generated model then has constraint kernels, and the runtime solves the constrained
dynamics Mt v' = Ft + Fi + A^T lambda, A v' = -gamma (docs/design.md, "Kinematic
constraints").
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Iterable

import sympy as sp

from gencoord.dsl.items import (Body, HolonomicConstraint, Point, VelocityConstraint, Wheel,
                                as_scalar, as_vector, caller_line)
from gencoord.dsl.rolling import contact_rows, positive_number, vanishes_near
from gencoord.errors import ModelError


def _rows(expr, what: str, line: int | None) -> list[sp.Expr]:
    """A scalar or a sequence of scalars as a list of expressions."""
    if isinstance(expr, sp.MatrixBase):
        return [as_scalar(entry, what, line) for entry in expr]
    if isinstance(expr, Iterable) and not isinstance(expr, (str, bytes)):
        rows = [as_scalar(entry, what, line) for entry in expr]
        if not rows:
            raise ModelError("is an empty list; give an expression or a list of them",
                             item=what, line=line)
        return rows
    return [as_scalar(expr, what, line)]


def _names(name: str, count: int, suffixes: str | None = None) -> list[str]:
    if count == 1:
        return [name]
    return [f"{name}_{suffixes[k]}" if suffixes else f"{name}_{k}" for k in range(count)]


class KinematicConstraints:
    """The kinematic-constraints part of a Model (model.py declares the lists)."""
    holonomic_constraints: list[HolonomicConstraint]
    velocity_constraints: list[VelocityConstraint]
    wheels: list[Wheel]
    dim: int
    coordinates: list
    parameters: list
    time: sp.Symbol

    if TYPE_CHECKING:  # GeneralizedSpeeds' (speeds.py), which Model also derives from
        def coordinate_rates(self) -> list[sp.Expr]: ...

        def on_manifold(self, values: list[float]) -> list[float]: ...

    def holonomic_constraint(self, expr, name: str | None = None) -> None:
        """C(q, t) = 0: an expression (or a list of them, one constraint each) of the
        coordinates, t, parameters and points' `.x`."""
        line = caller_line()
        name = name or f"constraint_{len(self.holonomic_constraints)}"
        rows = _rows(expr, f"holonomic constraint '{name}'", line)
        self.holonomic_constraints += [HolonomicConstraint(row_name, row, line=line)
                                       for row_name, row in zip(_names(name, len(rows)), rows)]

    def velocity_constraint(self, expr, name: str | None = None) -> None:
        """A(q, t) v + b(q, t) = 0: an expression (or a list of them) linear in the speeds
        (`model.rate(q)` of an ordinary coordinate), of the coordinates, t, parameters and
        points' `.x` and `.xdot`."""
        line = caller_line()
        name = name or f"velocity_constraint_{len(self.velocity_constraints)}"
        rows = _rows(expr, f"velocity constraint '{name}'", line)
        self.velocity_constraints += [VelocityConstraint(row_name, row, line=line)
                                      for row_name, row in zip(_names(name, len(rows)), rows)]

    def close_loop(self, a: Point, b: Point, name: str | None = None) -> None:
        """Closes a kinematic loop: points a and b (particles, body points, fixed points)
        coincide, dim holonomic constraints x_b - x_a = 0. The multipliers are the force on
        b from the loop, in the world's axes (and its opposite on a)."""
        line = caller_line()
        for point, which in ((a, "first"), (b, "second")):
            if not isinstance(point, Point):
                raise ModelError(f"the {which} point is {point!r}, not a point of the model; give "
                                 "particles, body points or fixed points",
                                 item=f"close_loop '{name or ''}'".replace(" ''", ""), line=line)
        name = name or f"{a.name}-{b.name}"
        self.holonomic_constraints += [
            HolonomicConstraint(row_name, xb - xa, line=line)
            for row_name, xa, xb in zip(_names(name, self.dim, "xyz"), a.x, b.x)]

    def rolling_wheel(self, body: Body, radius, axle=(0, 0, 1), center=(0, 0, 0),
                      name: str | None = None) -> None:
        """A wheel (a body) rolling without slipping on the ground plane z = 0 (3D): its
        material point at the contact does not move. `axle` is the wheel's axis and `center`
        its centre, both in the body's axes. Adds two velocity constraints (`<name>_x`,
        `<name>_y`: the contact point's velocity) and, where the coordinates do not already
        keep the wheel on the ground, the holonomic one `<name>_contact` (the contact
        point's height is 0)."""
        line = caller_line()
        name = name or f"{getattr(body, 'name', 'wheel')}_rolling"
        label = f"rolling wheel '{name}'"
        if self.dim != 3:
            raise ModelError("rolls on the ground plane z = 0 of a 3D model; this model is 2D",
                             item=label, line=line)
        if not isinstance(body, Body):
            raise ModelError(f"the wheel is {body!r}, not a body of the model; give the body "
                             "that model.body(...) returned", item=label, line=line)
        radius = as_scalar(radius, f"{label} radius", line)
        axle = as_vector(axle, f"{label} axle", 3, line)
        center = as_vector(center, f"{label} center", 3, line)
        if all(component == 0 for component in axle):
            raise ModelError("axle is zero; give the wheel's axis in the body's axes",
                             item=label, line=line)
        q = [c.symbol for c in self.coordinates]
        rows, height = contact_rows(body, radius, axle, center, q, self.coordinate_rates(),
                                    self.time)
        self.velocity_constraints += [VelocityConstraint(row_name, row, line=line, wheel=name)
                                      for row_name, row in zip(_names(name, 2, "xy"), rows)]
        self.wheels.append(Wheel(name, body, radius, axle, center, line=line))
        defaults = {p.symbol: sp.Float(p.default) for p in self.parameters}
        initial = self.on_manifold([c.initial for c in self.coordinates])
        if not vanishes_near(height, q, initial, self.time, defaults,
                             positive_number(radius, defaults)):
            self.holonomic_constraints.append(
                HolonomicConstraint(f"{name}_contact", height, line=line, wheel=name))

    @property
    def has_kinematic_constraints(self) -> bool:
        return bool(self.holonomic_constraints or self.velocity_constraints)
