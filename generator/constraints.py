"""Declared constraints: how far each is violated, its penalty force, and a check against X.

Every declared constraint must hold identically on the parameterization, C(X(q, t)) = 0 for
all q and t (DESIGN.md, "Parameterization pitfalls"). `verify_constraints` checks that
symbolically where simplification is cheap, otherwise at random samples, and refuses the
model naming the constraint and a violating sample. The maximal-coordinate model
(`maximal.py`) enforces the same constraints softly with the penalty forces below.
"""

from __future__ import annotations

import math
import random

import sympy as sp

from .derive import Kinematics
from .errors import ModelError
from .model import Model, Pin, Plane, Rod

SAMPLES = 256
RELATIVE_TOLERANCE = 1e-10
_CHEAP_OPS = 100  # try trigsimp only on residuals at most this big; sample the rest
SYMBOLIC_MAX_NQ = 6  # and only on models this small: n trigsimps cost seconds


def _norm(d: sp.Matrix) -> sp.Expr:
    return sp.sqrt(sum(component**2 for component in d))


def violation(constraint, kin) -> tuple[sp.Expr, sp.Expr]:
    """(signed or absolute violation, its natural scale) of one constraint under `kin`.

    rod: |x_b - x_a| - L (scale L); pin: |x - anchor| (scale 1 + |anchor|);
    plane: the signed distance (n.x - offset) / |n| (scale 1 + |offset| / |n|).
    """
    if isinstance(constraint, Rod):
        d = kin.position[constraint.b.name] - kin.position[constraint.a.name]
        return _norm(d) - constraint.length, constraint.length
    if isinstance(constraint, Pin):
        d = kin.position[constraint.particle.name] - constraint.anchor
        return _norm(d), 1 + _norm(constraint.anchor)
    if isinstance(constraint, Plane):
        n = constraint.normal
        x = kin.position[constraint.particle.name]
        return (n.dot(x) - constraint.offset) / _norm(n), 1 + sp.Abs(constraint.offset) / _norm(n)
    raise TypeError(f"unknown constraint {constraint!r}")


def _squared_residual(constraint, kin) -> sp.Expr:
    """A polynomial-friendly residual that is zero exactly when the constraint holds."""
    if isinstance(constraint, Rod):
        d = kin.position[constraint.b.name] - kin.position[constraint.a.name]
        return d.dot(d) - constraint.length**2
    if isinstance(constraint, Pin):
        d = kin.position[constraint.particle.name] - constraint.anchor
        return d.dot(d)
    n = constraint.normal
    return n.dot(kin.position[constraint.particle.name]) - constraint.offset


def penalty(constraint, kin, kappa: sp.Symbol, damping: sp.Symbol):
    """The penalty forces {point name: force} and energy that enforce a constraint softly.

    rod: the notes' strain spring of stiffness kappa (force per strain), with damping
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
        magnitude = kappa * (length - rest) / rest + damping * (vb - va).dot(direction) / rest
        energy = kappa * (length - rest)**2 / (2 * rest)
        return {constraint.b.name: -magnitude * direction,
                constraint.a.name: magnitude * direction}, energy
    if isinstance(constraint, Pin):
        x, v = kin.of(constraint.particle)
        anchor = constraint.anchor
        anchor_velocity = anchor.diff(kin.t)
        force = -kappa * (x - anchor) - damping * (v - anchor_velocity)
        return {constraint.particle.name: force}, kappa * (x - anchor).dot(x - anchor) / 2
    if isinstance(constraint, Plane):
        x, v = kin.of(constraint.particle)
        unit = constraint.normal / _norm(constraint.normal)
        distance = unit.dot(x) - constraint.offset / _norm(constraint.normal)
        rate = distance.diff(kin.t) + sum(distance.diff(xi) * vi for xi, vi in zip(x, v)
                                          if isinstance(xi, sp.Symbol))
        force = (-kappa * distance - damping * rate) * unit
        return {constraint.particle.name: force}, kappa * distance**2 / 2
    raise TypeError(f"unknown constraint {constraint!r}")


def _atomize_trig_arguments(expr: sp.Expr) -> sp.Expr:
    """Replaces each distinct sin/cos argument (say theta1 + theta2) by a fresh symbol.

    trigsimp then sees sin(u)^2 + cos(u)^2 instead of expanding sums of angles, which is
    exponential in their number. A residual that vanishes after this vanishes before it.
    """
    arguments = sorted({f.args[0] for f in expr.atoms(sp.sin, sp.cos)}, key=sp.default_sort_key)
    fresh = {a: sp.Dummy(f"u{k}", real=True) for k, a in enumerate(arguments)}
    return expr.xreplace({f: f.func(fresh[f.args[0]]) for f in expr.atoms(sp.sin, sp.cos)})


def _holds_symbolically(residual: sp.Expr) -> bool:
    if residual == 0:
        return True
    if sp.count_ops(residual) > _CHEAP_OPS:
        return False
    return sp.trigsimp(_atomize_trig_arguments(residual)) == 0


def verify_constraints(model: Model, seed: int = 20261121,
                       kin: Kinematics | None = None) -> None:
    """Refuses a model whose declared constraints do not hold identically on X(q, t).

    Parameters take their defaults; q is sampled in [-pi, pi] and t in [0, 10]. Symbolic
    proofs are tried only on models of up to SYMBOLIC_MAX_NQ coordinates; larger ones go
    straight to sampling, all constraints evaluated by one compiled function.
    """
    if not model.constraints:
        return
    kin = kin or Kinematics(model)  # the pipeline builds it once for every stage
    defaults = {p.symbol: sp.Float(p.default) for p in model.parameters}
    q = [c.symbol for c in model.coordinates]
    rng = random.Random(seed)
    samples = [([rng.uniform(-math.pi, math.pi) for _ in q], rng.uniform(0.0, 10.0))
               for _ in range(SAMPLES)]
    symbolic = len(q) <= SYMBOLIC_MAX_NQ
    sampled = [c for c in model.constraints if not (symbolic and _holds_symbolically(
        _squared_residual(c, kin).xreplace(defaults)))]
    if not sampled:
        return
    outputs = [sp.sympify(e).xreplace(defaults) for c in sampled for e in violation(c, kin)]
    evaluate = sp.lambdify([q, kin.t], outputs, modules="math")
    values = [(evaluate(point, t), point, t) for point, t in samples]
    for k, constraint in enumerate(sampled):
        for result, point, t in values:
            off, size = result[2 * k], result[2 * k + 1]
            if not abs(off) <= RELATIVE_TOLERANCE * abs(size):
                at = ", ".join(f"{c.name} = {v:.6g}" for c, v in zip(model.coordinates, point))
                raise ModelError(
                    f"does not hold on the parameterization: at {at}, t = {t:.6g} it is "
                    f"violated by {off:.6g} ({_describe(constraint)}). A declared constraint "
                    "must satisfy C(X(q, t)) = 0 for every q and t; fix the constraint or the "
                    "particle positions", item=constraint.label(), line=constraint.line)


def _describe(constraint) -> str:
    if isinstance(constraint, Rod):
        return f"|x_{constraint.b.name} - x_{constraint.a.name}| - ({constraint.length})"
    if isinstance(constraint, Pin):
        return f"|x_{constraint.particle.name} - anchor|"
    return f"signed distance of {constraint.particle.name} from the plane"
