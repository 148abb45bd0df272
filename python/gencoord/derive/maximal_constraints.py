# SPDX-License-Identifier: BSD-3-Clause
"""Kinematic constraints (closed loops, rolling) in the maximal-coordinate model.

In the maximal model every particle is free, so each row of a kinematic constraint must be
written in the particles' positions x and velocities xdot:

- a holonomic row C (a `close_loop`, or a `holonomic_constraint` written in points' `.x`)
  becomes a penalty spring: energy kappa C^2 / 2, force -(kappa C + c C') grad_x C, with c
  the penalty damping, as the declared constraints' pins;
- a velocity row a(x) xdot + b (a `velocity_constraint` written in points' `.x` and `.xdot`)
  becomes a viscous penalty, force -c_v (a xdot + b) a^T: a realization of the nonholonomic
  constraint by friction, which tends to it as c_v grows. c_v = sqrt(kappa m), m the mass of
  the wheel's body (or of the whole model for a user's row), so that its rate c_v / m grows
  like the penalty springs' frequencies sqrt(kappa / m) and the same explicit step suits both;
- a rolling wheel's rows are rebuilt from the wheel's point masses: the body's orientation
  is the linear fit F = sum m_k x_k r_k^T S^-1 (a rotation while the body is rigid), the
  contact point P the lowest point of the wheel's circle, its height P_z a holonomic row
  (always: nothing keeps a free wheel on the ground) and the velocity of the wheel's material
  point at P the two velocity rows. Their forces act at P, spread over the point masses by
  its affine weights: for a rigid wheel that is the height's gradient (P is the circle's
  lowest point, so turning the wheel moves it only to second order).

A row written in the coordinates q (the reduced model's only) has no maximal form: such a
model gets no maximal model, and `maximal_constraint_problem` says which row and why.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from gencoord.dsl.items import Body, HolonomicConstraint, VelocityConstraint, Wheel
from gencoord.dsl.model import Model


@dataclass
class HolonomicRow:
    """C(x, t) = 0 and the direction g (nx) of its penalty force -(kappa C + c g.xdot) g: the
    gradient of C, or for a wheel's contact height the vertical at the contact point."""
    label: str
    value: sp.Expr
    direction: list[sp.Expr]


@dataclass
class VelocityRow:
    """a(x) . xdot + b(x, t) = 0, and the mass that scales its viscous penalty."""
    label: str
    coefficients: list[sp.Expr]
    bias: sp.Expr
    mass: sp.Expr


@dataclass
class MaximalRows:
    holonomic: list[HolonomicRow]
    velocity: list[VelocityRow]


def _coordinate_symbols(model: Model) -> set[sp.Symbol]:
    symbols = {c.symbol for c in model.coordinates} | {c.rate for c in model.coordinates}
    return symbols | {s.symbol for s in model.joint_speeds}


def _is_flat(body: Body, defaults: dict) -> bool:
    """Whether the body's mass lies in a plane or on a line at the default parameters (a
    disk of no thickness): its point masses cannot fix its orientation."""
    assert body.second_moment is not None  # set with the point masses (bodies.py)
    moment = body.second_moment.xreplace(defaults)
    try:
        determinant, scale = float(moment.det()), float(moment.trace())
    except (TypeError, ValueError):
        return False  # not a number at the defaults: judged by the run, not here
    return not abs(determinant) > 1e-9 * abs(scale) ** 3


def maximal_constraint_problem(model: Model) -> str | None:
    """Why the model's kinematic constraints have no maximal form, or None."""
    defaults = {p.symbol: sp.Float(p.default) for p in model.parameters}
    for wheel in model.wheels:
        if _is_flat(wheel.body, defaults):
            at = f" (line {wheel.line})" if wheel.line else ""
            return (f"{wheel.label()}{at}: its body's mass lies in one plane (a disk of no "
                    "thickness, I_axle = I_1 + I_2), and the maximal-coordinate model places a "
                    "body by point masses off one plane; give the wheel some thickness")
    q = _coordinate_symbols(model)
    rows: list[HolonomicConstraint | VelocityConstraint] = [*model.holonomic_constraints,
                                                            *model.velocity_constraints]
    for row in rows:
        if not row.wheel and row.expr.free_symbols & q:
            at = f" (line {row.line})" if row.line else ""
            return (f"{row.label()}{at} is written in the coordinates; the maximal-coordinate "
                    "model needs it in the points' positions (`.x`) and velocities (`.xdot`), "
                    "as close_loop writes it")
    return None


def _body_fit(body: Body) -> tuple[sp.Matrix, sp.Matrix]:
    """(centre of mass, F) of a body from its point masses' positions x: F = R while the
    body is rigid."""
    count = len(body.particles)
    centre = sum((p.x for p in body.particles), sp.zeros(3, 1)) / count
    fit = sum((p.x * r.T for p, r in zip(body.particles, body.offsets)), sp.zeros(3, 3))
    return centre, body.mass / count * fit * body.second_moment_inverse()


def _at_point(weights: list[sp.Expr], body: Body, x: list[sp.Symbol],
              vector: sp.Matrix) -> list[sp.Expr]:
    """The nx coefficients that spread `vector` at a point of the body over its point masses
    with the point's affine weights (the point's velocity along `vector` is their dot
    product with xdot)."""
    column = {s: k for k, s in enumerate(x)}
    out = [sp.Integer(0)] * len(x)
    for w, particle in zip(weights, body.particles):
        for component, symbol in zip(vector, particle.x):
            out[column[symbol]] += w * component
    return out


def _wheel_rows(wheel: Wheel,
                x: list[sp.Symbol]) -> tuple[HolonomicRow, VelocityRow, VelocityRow]:
    """A wheel's contact height and contact velocity rows, in its body's point masses.

    The contact point P is the lowest point of the wheel's circle; its body coordinates (the
    wheel's centre plus F^T (P - hub) in the wheel's plane) give its affine weights, which
    carry the contact's forces and give the velocity of the wheel's material point there.
    Derivatives of P's position itself would divide by the point masses' spread across a thin
    wheel (millimetres); the weights of a point in the wheel's plane do not."""
    body = wheel.body
    centre, fit = _body_fit(body)
    hub = centre + fit * wheel.center
    axle = fit * wheel.axle
    axle = axle / sp.sqrt(axle.dot(axle))
    up = sp.Matrix([0, 0, 1])
    down = -(up - axle[2] * axle) / sp.sqrt(1 - axle[2] ** 2)
    offset = wheel.radius * down
    # the contact point in body axes: the hub, then the offset in the wheel's plane (F^T F = 1
    # for a rigid body; the offset's component along the axle, zero for a rigid body, would
    # only carry round-off magnified by the thin spread)
    local = fit.T * offset
    local -= local.dot(wheel.axle) / wheel.axle.dot(wheel.axle) * wheel.axle
    weights = body.affine_weights(wheel.center + local)
    contact = hub + offset
    label, mass = wheel.label(), body.mass
    return (HolonomicRow(f"{label} contact height", contact[2],
                         _at_point(weights, body, x, up)),
            VelocityRow(f"{label} contact velocity x",
                        _at_point(weights, body, x, sp.Matrix([1, 0, 0])), sp.Integer(0), mass),
            VelocityRow(f"{label} contact velocity y",
                        _at_point(weights, body, x, sp.Matrix([0, 1, 0])), sp.Integer(0), mass))


def maximal_rows(model: Model, point_substitution: dict[sp.Symbol, sp.Expr],
                 x: list[sp.Symbol], xdot: list[sp.Symbol]) -> MaximalRows:
    """The kinematic constraints in the maximal model's x and xdot (maximal_constraint_problem
    must be None): users' rows with every point's symbols replaced by its maximal position and
    velocity, then each wheel's rows."""
    rows = MaximalRows([], [])
    for holonomic in model.holonomic_constraints:
        if not holonomic.wheel:
            value = holonomic.expr.xreplace(point_substitution)
            rows.holonomic.append(HolonomicRow(holonomic.label(), value,
                                               [value.diff(s) for s in x]))
    total_mass = sum((p.mass for p in model.particles), sp.Integer(0))
    zero = {v: 0 for v in xdot}
    for row in model.velocity_constraints:
        if not row.wheel:
            value = row.expr.xreplace(point_substitution)
            rows.velocity.append(VelocityRow(row.label(), [value.diff(v) for v in xdot],
                                             value.xreplace(zero), total_mass))
    for wheel in model.wheels:
        height, along_x, along_y = _wheel_rows(wheel, x)
        rows.holonomic.append(height)
        rows.velocity += [along_x, along_y]
    return rows


def kinematic_penalties(rows: MaximalRows, xdot: list[sp.Symbol], t: sp.Symbol,
                        kappa: sp.Symbol, damping: sp.Symbol) -> tuple[sp.Matrix, sp.Expr]:
    """The penalty forces on x (len(xdot) entries) and the penalty energy of the rows."""
    force = sp.zeros(len(xdot), 1)
    energy = sp.Integer(0)
    for row in rows.holonomic:
        rate = row.value.diff(t) + sp.Add(*[g * v for g, v in zip(row.direction, xdot)])
        magnitude = kappa * row.value + damping * rate
        force -= sp.Matrix([magnitude * g for g in row.direction])
        energy += kappa * row.value**2 / 2
    for velocity in rows.velocity:
        value = velocity.bias + sp.Add(*[a * v for a, v in zip(velocity.coefficients, xdot)])
        viscosity = sp.sqrt(kappa * velocity.mass)
        force -= sp.Matrix([viscosity * value * a for a in velocity.coefficients])
    return force, energy
