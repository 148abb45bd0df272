# SPDX-License-Identifier: BSD-3-Clause
"""Declared constraints: how far each is violated, its penalty force, and a check against X.

Every declared constraint must hold identically on the parameterization, C(X(q, t)) = 0 for
all q, t and parameter values (docs/models.md, "What generation checks"). `verify_constraints`
checks that symbolically where a proof is cheap (trig_polynomial.py), otherwise at random
samples of q, t and the parameters, and refuses the model naming the constraint and a
violating sample. The maximal-coordinate model
(`maximal.py`) enforces the same constraints softly with the penalty forces below.
"""

from __future__ import annotations

import math
import random

import sympy as sp

from gencoord.checks.budget import Budget, BudgetSpent
from gencoord.derive.dense import Kinematics
from gencoord.errors import ModelError
from gencoord.symbolic.finite import finite_or_none
from gencoord.dsl.model import Model
from gencoord.dsl.items import BodyParticle, Pin, Plane, Point, Rod
from gencoord.symbolic.sums import difference, dot
from gencoord.symbolic.trig_polynomial import vanishes_identically

SAMPLES = 256
RELATIVE_TOLERANCE = 1e-10
SYMBOLIC_MAX_NQ = 6  # symbolic proofs only on models this small; larger ones are sampled
PROOF_SECONDS = 0.4  # CPU budget of the symbolic proofs; unproven constraints are sampled
SAMPLING_SECONDS = 0.4  # CPU budget of the sampling


def _norm(d: sp.Matrix) -> sp.Expr:
    return sp.sqrt(sum(component**2 for component in d))


def _anchor(pin: Pin, kin) -> tuple[sp.Matrix, sp.Matrix]:
    """(position, velocity) of a pin's anchor: a moving point's, or a vector's of t."""
    if isinstance(pin.anchor, Point):
        return kin.of(pin.anchor)
    return pin.anchor, pin.anchor.diff(kin.t)


def violation(constraint, kin) -> tuple[sp.Expr, sp.Expr]:
    """(signed or absolute violation, its natural scale) of one constraint under `kin`.

    rod: |x_b - x_a| - L (scale L); pin: |x - anchor| (scale 1 + |anchor|);
    plane: the signed distance (n.x - offset) / |n| (scale 1 + |offset| / |n|).
    """
    if isinstance(constraint, Rod):
        d = difference(kin.position[constraint.b.name], kin.position[constraint.a.name])
        return _norm(d) - constraint.length, constraint.length
    if isinstance(constraint, Pin):
        anchor = _anchor(constraint, kin)[0]
        d = difference(kin.position[constraint.particle.name], anchor)
        return _norm(d), 1 + _norm(anchor)
    if isinstance(constraint, Plane):
        n = constraint.normal
        x = kin.position[constraint.particle.name]
        return (dot(n, x) - constraint.offset) / _norm(n), 1 + sp.Abs(constraint.offset) / _norm(n)
    raise TypeError(f"unknown constraint {constraint!r}")


def _squared_residual(constraint, kin) -> sp.Expr:
    """A polynomial-friendly residual that is zero exactly when the constraint holds."""
    if isinstance(constraint, Rod):
        d = difference(kin.position[constraint.b.name], kin.position[constraint.a.name])
        return dot(d, d) - constraint.length**2
    if isinstance(constraint, Pin):
        d = kin.position[constraint.particle.name] - _anchor(constraint, kin)[0]
        return dot(d, d)
    n = constraint.normal
    return dot(n, kin.position[constraint.particle.name]) - constraint.offset


def penalty(constraint, kin, kappa: sp.Symbol, damping: sp.Symbol):
    """The penalty forces [(point, force)] and energy that enforce a constraint softly.

    rod: a strain spring of stiffness kappa (force per strain), with damping
    `damping ((v_b - v_a).d^) / L`; pin: a zero-length spring kappa (x - anchor(t)) to the
    (possibly moving) anchor; plane: a spring kappa along the unit normal on the signed
    distance. Damping acts on the rate of the same violation.
    """
    if isinstance(constraint, Rod):
        (xa, va), (xb, vb) = kin.of(constraint.a), kin.of(constraint.b)
        d = xb - xa
        length = _norm(d)
        direction = d / length
        rest = constraint.length
        magnitude = kappa * (length - rest) / rest + damping * dot(vb - va, direction) / rest
        energy = kappa * (length - rest)**2 / (2 * rest)
        return [(constraint.b, -magnitude * direction),
                (constraint.a, magnitude * direction)], energy
    if isinstance(constraint, Pin):
        x, v = kin.of(constraint.particle)
        anchor, anchor_velocity = _anchor(constraint, kin)
        force = -kappa * (x - anchor) - damping * (v - anchor_velocity)
        forces = [(constraint.particle, force)]
        if isinstance(constraint.anchor, Point):  # a joint: the anchor takes the reaction
            forces.append((constraint.anchor, -force))
        return forces, kappa * dot(x - anchor, x - anchor) / 2
    if isinstance(constraint, Plane):
        x, v = kin.of(constraint.particle)
        unit = constraint.normal / _norm(constraint.normal)
        distance = dot(unit, x) - constraint.offset / _norm(constraint.normal)
        rate = distance.diff(kin.t) + sum(distance.diff(xi) * vi for xi, vi in zip(x, v)
                                          if isinstance(xi, sp.Symbol))
        force = (-kappa * distance - damping * rate) * unit
        return [(constraint.particle, force)], kappa * distance**2 / 2
    raise TypeError(f"unknown constraint {constraint!r}")


def _proven(constraints: list, kin) -> set[int]:
    """Indices of the constraints proven to hold symbolically, for every value of the
    parameters, within PROOF_SECONDS."""
    proven = set()
    budget = Budget(PROOF_SECONDS)
    try:
        with budget.interrupting():
            for k, constraint in enumerate(constraints):
                if vanishes_identically(_squared_residual(constraint, kin)):
                    proven.add(k)
    except BudgetSpent:
        pass  # the rest are sampled
    return proven


def _compile(constraints: list, kin, q: list, params: list):
    """A function (q, params, t) -> [violation, scale, violation, scale, ...]."""
    outputs = [sp.sympify(e) for c in constraints for e in violation(c, kin)]
    return sp.lambdify([q, params, kin.t], outputs, modules="math")


def _sampled_value(default: float, rng: random.Random) -> float:
    """A parameter value near its default: within a factor 2, or in [0.1, 1] for a zero
    default (a constraint that holds at the default only must show at the samples)."""
    return default * rng.uniform(0.5, 2.0) if default != 0 else rng.uniform(0.1, 1.0)


def _finite_samples(constraints: list, kin, q: list, params: list, samples: list):
    """Per constraint, the samples (violation, scale, q, parameter values, t) where it
    evaluates to finite numbers (X may leave its domain: sqrt of a negative, a pole), and
    whether sampling stopped at its time budget."""
    together = _compile(constraints, kin, q, params)
    alone = None  # one function per constraint, compiled when a sample fails together
    found: list[list] = [[] for _ in constraints]
    budget = Budget(SAMPLING_SECONDS)
    for point, values_of_params, t in samples:
        if budget.spent():
            return found, True
        values = finite_or_none(together, point, values_of_params, t)
        if values is not None:
            for k in range(len(constraints)):
                found[k].append((values[2 * k], values[2 * k + 1], point, values_of_params, t))
            continue
        alone = alone or [_compile([c], kin, q, params) for c in constraints]
        for k, function in enumerate(alone):
            pair = finite_or_none(function, point, values_of_params, t)
            if pair is not None:
                found[k].append((pair[0], pair[1], point, values_of_params, t))
    return found, False


def verify_constraints(model: Model, seed: int = 20261121,
                       kin: Kinematics | None = None) -> list[str]:
    """Refuses a model whose declared constraints do not hold identically on X(q, t).

    q is sampled in [-pi, pi], t in [0, 10] and each parameter near its default
    (_sampled_value); symbolic proofs keep the parameters as symbols. Proofs are tried only
    on models of up to SYMBOLIC_MAX_NQ coordinates; larger ones go straight to sampling, all
    constraints evaluated by one compiled function. Returns notes
    for the report: a constraint that could not be evaluated anywhere, or sampling stopped
    by its time budget.
    """
    declared = [c for c in model.constraints if not _rigid_by_construction(c)]
    if not declared:
        return []
    kin = kin or Kinematics(model)  # the pipeline builds it once for every stage
    q = [c.symbol for c in model.coordinates]
    params = [p.symbol for p in model.parameters]
    rng = random.Random(seed)
    samples = [(model.on_manifold([rng.uniform(-math.pi, math.pi) for _ in q]),
                [_sampled_value(p.default, rng) for p in model.parameters],
                rng.uniform(0.0, 10.0)) for _ in range(SAMPLES)]
    proven = _proven(declared, kin) if len(q) <= SYMBOLIC_MAX_NQ else set()
    sampled = [c for k, c in enumerate(declared) if k not in proven]
    if not sampled:
        return []
    found, stopped = _finite_samples(sampled, kin, q, params, samples)
    notes = []
    for constraint, values in zip(sampled, found):
        for off, size, point, values_of_params, t in values:
            if not abs(off) <= RELATIVE_TOLERANCE * abs(size):
                at = ", ".join(f"{c.name} = {v:.6g}" for c, v in zip(model.coordinates, point))
                at += "".join(f", {p.name} = {v:.6g}"
                              for p, v in zip(model.parameters, values_of_params))
                raise ModelError(
                    f"does not hold on the parameterization: at {at}, t = {t:.6g} it is "
                    f"violated by {off:.6g} ({_describe(constraint)}). A declared constraint "
                    "must satisfy C(X(q, t)) = 0 for every q, t and parameter value; fix the "
                    "constraint or the particle positions",
                    item=constraint.label(), line=constraint.line)
        if not values and not stopped:
            notes.append(f"Constraint check skipped for {constraint.label()}: not finite at "
                         f"any of {SAMPLES} sampled configurations (q in [-pi, pi])")
    if stopped:
        notes.append(f"Constraint check stopped at its time budget ({SAMPLING_SECONDS:g} s CPU) "
                     f"before all {SAMPLES} samples; constraints held where evaluated")
    return notes


def _rigid_by_construction(constraint) -> bool:
    """A rod between two point masses of one body: they move with the body's frame; a pin
    that holds a joint's halves together: the joint's motion keeps them on each other."""
    if isinstance(constraint, Pin):
        return constraint.joint is not None
    return (isinstance(constraint, Rod) and isinstance(constraint.a, BodyParticle)
            and isinstance(constraint.b, BodyParticle)
            and constraint.a.body_name == constraint.b.body_name)


def _describe(constraint) -> str:
    if isinstance(constraint, Rod):
        return f"|x_{constraint.b.name} - x_{constraint.a.name}| - ({constraint.length})"
    if isinstance(constraint, Pin):
        return f"|x_{constraint.particle.name} - anchor|"
    return f"signed distance of {constraint.particle.name} from the plane"
