# SPDX-License-Identifier: BSD-3-Clause
"""Checks of the kinematic constraints (dsl/kinematic_constraints.py), and the initial state
put on them.

Refused, with the constraint's line: a holonomic constraint that does not depend on the
coordinates, a velocity constraint that is not linear in the speeds or does not involve
them, as many constraints as speeds (no motion left), and a set whose Jacobian A is
rank-deficient at the initial state (a redundant or inconsistent constraint, named). The
model file's initial coordinates are moved onto C(q, 0) = 0 by Gauss-Newton steps, and its
initial speeds onto A v + b = 0 by the least change; the report says what moved.
"""

from __future__ import annotations

import math
import random

import sympy as sp

from gencoord.checks.conditioning import least_change_step
from gencoord.derive.dense import Kinematics
from gencoord.derive.differentiate import termwise_jacobian
from gencoord.derive.kinematic_constraints import ConstraintDerivation
from gencoord.dsl.model import Model
from gencoord.errors import ModelError

NEWTON_STEPS = 50
SPEED_SAMPLES = 8  # configurations at which a velocity row must involve some speed
RANK_TOLERANCE = 1e-9       # a row is dependent when its part off the others is this small
POSITION_TOLERANCE = 1e-13  # |C| the initial coordinates are brought to (relative to 1 + |q|)


def _largest(values: list[float]) -> float:
    return max((abs(value) for value in values), default=0.0)


def _dependent_row(matrix: list[list[float]]) -> int | None:
    """The first row that is a combination of those before it (Gram-Schmidt), or None."""
    basis: list[list[float]] = []
    for k, row in enumerate(matrix):
        rest = list(row)
        for b in basis:
            projection = sum(x * y for x, y in zip(rest, b))
            rest = [x - projection * y for x, y in zip(rest, b)]
        norm, size = math.sqrt(sum(x * x for x in rest)), math.sqrt(sum(x * x for x in row))
        if norm <= RANK_TOLERANCE * max(size, 1e-300):
            return k
        basis.append([x / norm for x in rest])
    return None


def _varies_with_speeds(model: Model, kin: Kinematics, gradient: list[sp.Expr]) -> bool:
    """Whether a velocity row's gradient in the speeds is nonzero: not identically zero in
    form, and nonzero at some random configuration (parameters at their defaults)."""
    entries = [entry for entry in gradient if not entry.is_zero]
    if not entries:
        return False
    values = sp.lambdify([kin.q, kin.t], [e.xreplace(kin.defaults) for e in entries],
                         modules="math")
    rng = random.Random(5)
    for _ in range(SPEED_SAMPLES):
        q = model.on_manifold([rng.uniform(-math.pi, math.pi) for _ in kin.q])
        try:
            if any(abs(value) > 1e-12 for value in values(q, rng.uniform(0, 1))):
                return True
        except (ValueError, ZeroDivisionError, OverflowError, TypeError):
            return True  # outside X's domain: not shown to vanish
    return False


def _check_each(model: Model, kin: Kinematics, c: ConstraintDerivation) -> None:
    """Each row's own checks."""
    q, v = set(kin.q), set(kin.v)
    for item, expr in zip(model.holonomic_constraints, c.holonomic):
        if not expr.free_symbols & q:
            raise ModelError("does not depend on the coordinates, so it constrains nothing or "
                             "cannot hold; write C(q, t) = 0 as an expression of them",
                             item=item.label(), line=item.line)
    for k, velocity_row in enumerate(model.velocity_constraints):
        row = c.num_holonomic + k
        if any(c.jacobian[row, j].free_symbols & v for j in range(len(kin.v))):
            raise ModelError("is not linear in the speeds; a velocity constraint is "
                             "A(q, t) v + b(q, t) = 0", item=velocity_row.label(),
                             line=velocity_row.line)
        if not _varies_with_speeds(model, kin, [c.jacobian[row, j] for j in range(len(kin.v))]):
            raise ModelError("does not involve the speeds; a condition on the coordinates "
                             "alone is a model.holonomic_constraint(...)",
                             item=velocity_row.label(), line=velocity_row.line)


def _project_initial_q(model: Model, kin: Kinematics, holonomic: sp.Matrix) -> list[str]:
    """Moves the initial coordinates onto C(q, 0) = 0; notes what moved."""
    if not holonomic:
        return []
    q0 = model.on_manifold([c.initial for c in model.coordinates])
    at_defaults = holonomic.xreplace(kin.defaults).subs(kin.t, 0)
    residual = sp.lambdify([kin.q], list(at_defaults), modules="math")
    jacobian = sp.lambdify([kin.q], termwise_jacobian(at_defaults, kin.q).tolist(),
                           modules="math")
    q = list(q0)
    first = model.holonomic_constraints[0]
    c = [math.inf] * len(holonomic)
    for _ in range(NEWTON_STEPS):
        try:
            c = residual(q)
            if _largest(c) <= POSITION_TOLERANCE * (1 + _largest(q)):
                break
            step = least_change_step(jacobian(q), c)
        except (ZeroDivisionError, ValueError, OverflowError):
            step = None
        if step is None or not all(map(math.isfinite, step)):
            break
        q = model.on_manifold([a + b for a, b in zip(q, step)])
    else:
        c = residual(q)
    tolerance = POSITION_TOLERANCE * (1 + _largest(q)) * 1e3
    unmet = [k for k in range(len(c)) if not abs(c[k]) <= tolerance]
    if unmet:
        items = model.holonomic_constraints
        last = items[unmet[-1]]
        others = [f"'{items[k].name}'" for k in unmet[:-1]]
        residuals = ", ".join(f"{items[k].name} {c[k]:.3g}" for k in unmet)
        rest = " while the other holonomic constraints hold" if len(items) > len(unmet) else ""
        raise ModelError("cannot be met near the initial coordinates"
                         + (f" together with {', '.join(others)}" if others else "") + rest
                         + f" (residuals after Gauss-Newton steps: {residuals}): the constraints "
                         "are inconsistent there, or the initial values are far from them; "
                         "give initial values that nearly satisfy them",
                         item=last.label(), line=last.line or first.line)
    moved = [(coordinate, old, new) for coordinate, old, new in zip(model.coordinates, q0, q)
             if abs(new - old) > 1e-15 * (1 + abs(old))]
    for coordinate, _, new in moved:
        coordinate.initial = new
    if not moved:
        return []
    return ["initial coordinates moved onto the holonomic constraints: " + ", ".join(
        f"{c.name} {old:.6g} -> {new:.17g}" for c, old, new in moved)]


def check_kinematic_constraints(model: Model, c: ConstraintDerivation | None,
                                kin: Kinematics) -> list[str]:
    """Raises ModelError for a constraint that cannot be used; puts the initial state on the
    constraints `c` (derive_kinematic_constraints) and returns notes for the report."""
    if c is None:
        return []
    if model.charts:
        raise ModelError("kinematic constraints in an atlas of charts are not supported; "
                         "use one chart", item="model", line=model.line)
    _check_each(model, kin, c)
    rows = [*model.holonomic_constraints, *model.velocity_constraints]
    if len(rows) >= model.nv:
        raise ModelError(f"{len(rows)} constraints on {model.nv} speeds leave no motion; a "
                         "constrained model needs fewer constraints than speeds",
                         item=rows[-1].label(), line=rows[-1].line)
    notes = _project_initial_q(model, kin, c.holonomic)
    # the velocity level at the initial state: A must have full row rank there
    point = {**kin.defaults, **dict(zip(kin.q, (c.initial for c in model.coordinates))),
             kin.t: 0}
    a = [[float(entry) for entry in c.jacobian.row(i).xreplace(point)] for i in range(len(rows))]
    dependent = _dependent_row(a)
    if dependent is not None:
        item = rows[dependent]
        raise ModelError("is redundant or inconsistent at the initial state: its row of the "
                         "constraint Jacobian A is a combination of the rows before it; remove "
                         "it, or start where the constraints are independent",
                         item=item.label(), line=item.line)
    speeds = model.speeds
    v0 = [s.initial for s in speeds]
    residual = [float(r) for r in c.velocity.xreplace(point).xreplace(dict(zip(kin.v, v0)))]
    if _largest(residual) > 1e-15 * (1 + _largest(v0)):
        step = least_change_step(a, residual)
        assert step is not None  # A's rows are independent: checked above
        v1 = [x + dx for x, dx in zip(v0, step)]
        _set_initial_speeds(model, v1)
        notes.append("initial speeds moved onto the velocity constraints (least change): "
                     + ", ".join(f"{s.name} {old:.6g} -> {new:.17g}"
                                 for s, old, new in zip(speeds, v0, v1) if new != old))
    return notes


def _set_initial_speeds(model: Model, values: list[float]) -> None:
    by_speed = dict(zip((s.symbol for s in model.speeds), values))
    for coordinate in model.coordinates:
        if coordinate.rate in by_speed:
            coordinate.initial_rate = by_speed[coordinate.rate]
    for speed in model.joint_speeds:
        speed.initial = by_speed[speed.symbol]
