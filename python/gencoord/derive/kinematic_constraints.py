# SPDX-License-Identifier: BSD-3-Clause
"""The kinematic constraints' equations (dsl/kinematic_constraints.py), for the kernels and
the checks.

Holonomic rows C(q, t) = 0 come first, then the velocity rows. At the velocity level every
row is linear in the speeds,

    A(q, t) v + b(q, t) = 0,   A = [C_q G; A_n],   b = [C_t; b_n],

and differentiating once more at v' = 0 gives the acceleration-level bias gamma:
A v' + gamma = 0 along every motion that keeps the constraints.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from gencoord.derive.dense import Kinematics, bias_acceleration
from gencoord.derive.differentiate import termwise_jacobian
from gencoord.dsl.model import Model


@dataclass
class ConstraintDerivation:
    names: list[str]                 # holonomic rows first, then the velocity rows
    holonomic: sp.Matrix             # nh: C(q, t)
    holonomic_jacobian: sp.Matrix    # nh x nq: dC/dq (a Newton step on q's embedding)
    jacobian: sp.Matrix              # nc x nv: A
    velocity: sp.Matrix              # nc: A v + b
    bias: sp.Matrix                  # nc: gamma, with A v' + gamma = 0

    @property
    def num_holonomic(self) -> int:
        return self.holonomic.shape[0]


def _column(entries: list[sp.Expr]) -> sp.Matrix:
    return sp.Matrix(len(entries), 1, entries)


def holonomic_expressions(model: Model, kin: Kinematics) -> sp.Matrix:
    """C(q, t), points' `.x` replaced by their positions."""
    return _column([sp.sympify(c.expr).xreplace(kin.point_substitution)
                    for c in model.holonomic_constraints])


def velocity_expressions(model: Model, kin: Kinematics) -> sp.Matrix:
    """The velocity rows A_n v + b_n, points' `.x` and `.xdot` replaced."""
    return _column([sp.sympify(c.expr).xreplace(kin.point_substitution)
                    for c in model.velocity_constraints])


def derive_kinematic_constraints(model: Model, kin: Kinematics) -> ConstraintDerivation | None:
    """The constraint equations of `model`; None when it declares none."""
    if not model.has_kinematic_constraints:
        return None
    holonomic = holonomic_expressions(model, kin)
    holonomic_jacobian = termwise_jacobian(holonomic, kin.q)
    holonomic_velocity = (kin.to_speeds(holonomic_jacobian) * sp.Matrix(kin.v)
                          + holonomic.diff(kin.t))
    velocity = sp.Matrix.vstack(holonomic_velocity, velocity_expressions(model, kin))
    jacobian = termwise_jacobian(velocity, kin.v)
    return ConstraintDerivation(
        names=[c.name for c in (*model.holonomic_constraints, *model.velocity_constraints)],
        holonomic=holonomic, holonomic_jacobian=holonomic_jacobian, jacobian=jacobian,
        velocity=velocity, bias=bias_acceleration(velocity, kin.q, kin.rates, kin.t))
