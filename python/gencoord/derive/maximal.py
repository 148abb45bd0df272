# SPDX-License-Identifier: BSD-3-Clause
"""The maximal-coordinate model of the same file: free particles, penalty constraints.

Every particle moves freely in R^d (x has dN entries); the same gravity, springs, dampers and
user forces act on it, and each declared constraint becomes a stiff penalty force of
stiffness `kappa` and damping `penalty_damping` (constraints.penalty). Forces acting directly
on q (joint torques) have no x-space form of their own: the runtime maps them through the
inverse map. The runtime integrates this model and compares it with the reduced one.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from gencoord.dsl.bodies import force_shares
from gencoord.checks.constraints import penalty, violation
from gencoord.derive.dense import particle_forces, x_space_potential
from gencoord.derive.maximal_constraints import (kinematic_penalties, maximal_constraint_problem,
                                                 maximal_rows)
from gencoord.dsl.model import Model
from gencoord.dsl.items import Point
from gencoord.derive.structured import Intermediates

KAPPA = sp.Symbol("kappa", positive=True)
PENALTY_DAMPING = sp.Symbol("penalty_damping", nonnegative=True)


class MaximalKinematics:
    """Point positions and velocities with every particle free: x and xdot are symbols."""

    def __init__(self, model: Model):
        self.t = model.time
        self.position: dict[str, sp.Matrix] = {}
        self.velocity: dict[str, sp.Matrix] = {}
        for p in model.particles:
            self.position[p.name], self.velocity[p.name] = p.x, p.xdot
        for f in model.fixed_points:
            self.position[f.name], self.velocity[f.name] = f.position, f.position.diff(self.t)
        zero = sp.zeros(model.dim, 1)
        for body in model.bodies:
            for body_point in body.points:  # the affine combination of the body's point masses
                pairs = list(zip(body_point.weights, body.particles))
                self.position[body_point.name] = sum((w * p.x for w, p in pairs), zero)
                self.velocity[body_point.name] = sum((w * p.xdot for w, p in pairs), zero)
        self.point_substitution: dict[sp.Symbol, sp.Expr] = {}
        particles = {p.name for p in model.particles}
        for point in model.points:
            if point.name not in particles:
                self.point_substitution.update(zip(point.x, self.position[point.name]))
                self.point_substitution.update(zip(point.xdot, self.velocity[point.name]))

    def of(self, point: Point) -> tuple[sp.Matrix, sp.Matrix]:
        return self.position[point.name], self.velocity[point.name]


@dataclass
class MaximalDerivation:
    x: list[sp.Symbol]                  # nx position symbols, particles stacked
    xdot: list[sp.Symbol]               # nx velocity symbols
    external_forces: sp.Matrix          # nx: gravity, springs, dampers, user forces
    penalty_forces: sp.Matrix           # nx: the constraints' penalty forces
    total_forces: sp.Matrix             # nx: F_ext + F_pen, whose Jacobians are emitted
    force_jacobian_x: list[tuple[int, int]]     # (row, column) of d(F_ext + F_pen)/dx entries
    force_jacobian_xdot: list[tuple[int, int]]  # the same for d(F_ext + F_pen)/dxdot
    # their values, differentiated symbolically; None: forward mode after CSE
    # (optimize/optimizer.py)
    force_jacobian_x_values: list[sp.Expr] | None
    force_jacobian_xdot_values: list[sp.Expr] | None
    potential_energy: sp.Expr           # x-space V (gravity, springs, user potentials)
    penalty_energy: sp.Expr
    violations: sp.Matrix               # one per declared constraint
    constraint_names: list[str]
    # the first entries of violations: the declared constraints, which hold on X(q, t); the
    # kinematic constraints' rows follow
    declared_constraints: int
    # the named intermediates the forces are written in (derive_maximal)
    definitions: list[tuple[sp.Symbol, sp.Expr]]


def _values(force: sp.Matrix, variables: list[sp.Symbol], pattern: list[tuple[int, int]]):
    """The entries at `pattern`, differentiated symbolically (small models: SymPy cancels)."""
    return [force[r].diff(variables[c]) for r, c in pattern]


def _pattern_through(force: sp.Matrix, variables: list[sp.Symbol],
                     definitions: list[tuple[sp.Symbol, sp.Expr]]) -> list[tuple[int, int]]:
    """(row, column) of each entry of d force / d variables that can be nonzero; a variable
    counts where it enters through any of the named intermediates the force reads.

    Structural: an entry whose derivative happens to cancel to 0 is kept (and emitted as 0).
    For large models the values are taken later by forward mode through the CSE'd force code
    (differentiate.py), a few operations per entry instead of differentiating each row's
    expression tree.
    """
    column = {w: c for c, w in enumerate(variables)}
    reaches: dict[sp.Symbol, set[int]] = {}   # intermediate -> the columns it depends on

    def columns(expr: sp.Expr) -> set[int]:
        return set().union(*[reaches.get(s, {column[s]} if s in column else set())
                             for s in expr.free_symbols])

    for symbol, expr in definitions:
        reaches[symbol] = columns(expr)
    return [(r, c) for r in range(force.shape[0]) for c in sorted(columns(force[r]))]


def has_maximal_model(model: Model) -> bool:
    """Whether the model can have a maximal-coordinate (penalty) model: not one whose kinematic
    constraints are written in the coordinates (maximal_constraints.py)."""
    return why_no_maximal_model(model) is None


def why_no_maximal_model(model: Model) -> str | None:
    """Why the model can have no maximal-coordinate model, or None."""
    return maximal_constraint_problem(model)


def derive_maximal(model: Model, symbolic_jacobians: bool = True,
                   named: bool = False) -> MaximalDerivation:
    """The maximal model's outputs, as expressions of x, xdot, t and the parameters.

    `named` (for the CSE of large models, without `symbolic_jacobians`): each constraint's
    penalty force is a named intermediate (`definitions`) before a body shares it among its
    point masses, so the eight particles of a joint's two bodies read one pin force."""
    if named and symbolic_jacobians:
        raise ValueError("named forces are differentiated after the CSE, not symbolically")
    kin = MaximalKinematics(model)
    names = Intermediates(prefix="__m") if named else None
    x = [s for p in model.particles for s in p.x]
    xdot = [s for p in model.particles for s in p.xdot]
    stack = lambda per_particle: sp.Matrix.vstack(*[per_particle[p.name]  # noqa: E731
                                                    for p in model.particles])
    external = stack(particle_forces(model, kin))

    penalties = {p.name: sp.zeros(model.dim, 1) for p in model.particles}
    penalty_energy = sp.Integer(0)
    for constraint in model.constraints:
        forces, energy = penalty(constraint, kin, KAPPA, PENALTY_DAMPING)
        for point, force in forces:
            if names is not None:
                force = names.vector(force)
            for target, share in force_shares(point, force):
                if target.name in penalties:  # a fixed point takes its reaction itself
                    penalties[target.name] = penalties[target.name] + share
        penalty_energy += energy
    rows = maximal_rows(model, kin.point_substitution, x, xdot)
    kinematic, kinematic_energy = kinematic_penalties(rows, xdot, model.time, KAPPA,
                                                      PENALTY_DAMPING)
    penalty_total = stack(penalties) + kinematic
    penalty_energy += kinematic_energy
    total = external + penalty_total
    definitions = names.definitions if names is not None else []
    pattern_x = _pattern_through(total, x, definitions)
    pattern_xdot = _pattern_through(total, xdot, definitions)
    return MaximalDerivation(
        x=x, xdot=xdot, external_forces=external, penalty_forces=penalty_total,
        total_forces=total, force_jacobian_x=pattern_x, force_jacobian_xdot=pattern_xdot,
        force_jacobian_x_values=_values(total, x, pattern_x) if symbolic_jacobians else None,
        force_jacobian_xdot_values=(_values(total, xdot, pattern_xdot) if symbolic_jacobians
                                    else None),
        potential_energy=x_space_potential(model, kin), penalty_energy=penalty_energy,
        violations=sp.Matrix([violation(c, kin)[0] for c in model.constraints]
                             + [row.value for row in rows.holonomic]),
        constraint_names=[c.label() for c in model.constraints]
        + [row.label for row in rows.holonomic],
        declared_constraints=len(model.constraints), definitions=definitions)
