# SPDX-License-Identifier: BSD-3-Clause
"""Joint limits: a coordinate kept in its range [lower, upper] while the model runs, and its
speed and effort ratings, reported where a run exceeds them.

A limit is no force and no constraint of the equations of motion: the generated header lists
the limited coordinates, their ranges and ratings, and the runtime enforces the ranges after
each step (gencoord/model/joint_limits.hpp): a coordinate past its limit is put back on it, and
an inelastic impulse through the mass matrix stops its speed into the limit. The effort rating
bounds the generalized force the model's control inputs apply at the coordinate's speed (a
motor's torque). Joints take theirs from `Limits` (URDF `<limit lower upper effort velocity>`;
a continuous joint has no range).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import sympy as sp

from gencoord.errors import ModelError
from gencoord.dsl.items import Coordinate, Item, caller_line


@dataclass
class CoordinateLimit(Item):
    """The range of one coordinate and the ratings of its speed and effort; what is not given
    is infinite."""
    coordinate: Coordinate
    lower: float
    upper: float
    velocity: float = math.inf
    effort: float = math.inf
    kind = "joint limit"


class JointLimits:
    """The joint-limits part of a Model (model.py declares the list)."""
    limits: list[CoordinateLimit]

    def _coordinate_of(self, symbol: sp.Symbol, where: str, line: int | None) -> Coordinate:
        raise NotImplementedError  # Model's: the declared coordinate, or a ModelError

    def limit(self, coordinate: sp.Symbol, lower=None, upper=None, velocity=None,
              name: str | None = None, effort=None) -> None:
        """Keeps `coordinate` in [lower, upper] (either may be None: no limit on that side),
        rates its speed at `velocity` and the generalized force the control inputs apply at
        it at `effort` (either above its rating is reported, not prevented).

        The coordinate must have its own speed (not a free or ball joint's quaternion).
        Equal ends lock the coordinate at that value.
        """
        line = caller_line()
        target = self._coordinate_of(coordinate, "limit", line)
        label = f"joint limit '{name or target.name}'"
        given = {}
        for what, value in (("lower end", lower), ("upper end", upper),
                            ("velocity rating", velocity), ("effort rating", effort)):
            if value is None:
                continue
            try:
                given[what] = float(value)
            except (TypeError, ValueError):
                raise ModelError(f"its {what} must be a number, not {value!r}", item=label,
                                 line=line) from None
            if not math.isfinite(given[what]):
                raise ModelError(f"its {what} must be finite, not {given[what]}; leave it out "
                                 "(None) for no limit", item=label, line=line)
        if not given:
            raise ModelError("give a lower end, an upper end, a velocity or effort rating or "
                             "some of them", item=label, line=line)
        lower, upper = given.get("lower end", -math.inf), given.get("upper end", math.inf)
        velocity = given.get("velocity rating", math.inf)
        effort = given.get("effort rating", math.inf)
        if lower > upper:
            raise ModelError(f"its lower end {lower:g} exceeds its upper end {upper:g}",
                             item=label, line=line)
        for what, rating in (("velocity", velocity), ("effort", effort)):
            if not rating > 0:
                raise ModelError(f"its {what} rating must be positive, not {rating:g}",
                                 item=label, line=line)
        if any(limit.coordinate is target for limit in self.limits):
            raise ModelError(f"{target.name} is limited twice; give it one range", item=label,
                             line=line)
        self.limits.append(CoordinateLimit(name or target.name, target, lower, upper, velocity,
                                           effort, line=line))
