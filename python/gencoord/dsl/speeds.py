# SPDX-License-Identifier: BSD-3-Clause
"""Generalized speeds: v, and the kinematic equation q' = G(q) v.

An ordinary coordinate's speed is its rate (v = q', the same symbol). A free or ball joint
(joints.py) has a unit quaternion among its coordinates, whose rate is no speed of its own:
the joint declares its coordinates without speeds, its twist components as speeds, and each
coordinate's rate in terms of them. The model then has nv < nq speeds.
"""

from __future__ import annotations

import math

import sympy as sp

from gencoord.dsl.items import Coordinate, Speed, caller_line


class GeneralizedSpeeds:
    """The speeds part of a Model (model.py declares the lists)."""
    coordinates: list[Coordinate]
    _speed_order: list[Coordinate | Speed]
    rates: dict[sp.Symbol, sp.Expr]
    quaternions: list[int]

    def speed(self, name: str, description: str, initial: float = 0.0) -> sp.Symbol:
        """Declares a generalized speed that is no coordinate's rate (a joint's twist
        component); returns its symbol."""
        speed = Speed(name, sp.Symbol(name, real=True), sp.Symbol(f"{name}_ddot", real=True),
                      description, float(initial), line=caller_line())
        self._speed_order.append(speed)
        return speed.symbol

    @property
    def speeds(self) -> list[Speed]:
        """v, in declaration order; an ordinary coordinate's speed is its rate."""
        return [item if isinstance(item, Speed) else
                Speed(item.name, item.rate, item.acceleration, item.description,
                      item.initial_rate, line=item.line)
                for item in self._speed_order]

    @property
    def joint_speeds(self) -> list[Speed]:
        """The speeds that are no coordinate's rate: free and ball joints' twists."""
        return [item for item in self._speed_order if isinstance(item, Speed)]

    def coordinate_rates(self) -> list[sp.Expr]:
        """q' = G(q) v, one expression per coordinate."""
        return [self.rates.get(c.symbol, c.rate) for c in self.coordinates]

    @property
    def has_generalized_speeds(self) -> bool:
        """Whether some q' is not a speed (a free or ball joint): nv < nq, q' = G(q) v."""
        return bool(self.rates)

    def on_manifold(self, values: list[float]) -> list[float]:
        """Coordinate values with each unit quaternion divided by its norm (the checks'
        random samples)."""
        values = list(values)
        for start in self.quaternions:
            part = values[start:start + 4]
            norm = math.sqrt(sum(c * c for c in part))
            values[start:start + 4] = [c / norm for c in part] if norm > 0 else [1.0, 0, 0, 0]
        return values

    @property
    def nv(self) -> int:
        return len(self._speed_order)
