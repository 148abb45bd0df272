# SPDX-License-Identifier: BSD-3-Clause
"""Whether a model's applied forces at rest are conservative: the fact a test of
potential_energy relies on, emitted as the model struct's `forces_have_potential`
(generate/stages.py
decides it with the other analyses)."""

from __future__ import annotations

import sympy as sp

from gencoord.derive.dense import Kinematics
from gencoord.dsl.items import GeneralizedForce, ParticleForce
from gencoord.dsl.model import Model


def _vanishes(expr) -> bool:
    return all(sp.simplify(e) == 0 for e in sp.Matrix([expr]))


def forces_have_potential(model: Model, kin: Kinematics | None = None) -> bool:
    """True when at rest (v = 0) the applied forces are -dV/dq, V the potential energy.

    Forces with a declared potential (gravity, springs, joint springs, user forces given one)
    are -dV/dq at any v, so what decides is whether every force without one vanishes at rest.
    At rest a point still moves with dX/dt, so damping is zero only between points whose
    positions do not depend on t; a user force must vanish identically once every point's
    position and velocity are put in. `kin`: the model's Kinematics, if already built.
    """
    t = model.time
    kin = kin or Kinematics(model)
    still = {speed.symbol: 0 for speed in model.speeds}
    points = {symbol: point for point in model.points for symbol in (*point.x, *point.xdot)}

    def at_rest(expr):
        """expr with v = 0 and each point it reads put in: x, and xdot = J v + X_t = X_t."""
        values = dict(still)
        for point in {points[s].name: points[s] for s in expr.free_symbols
                      if s in points}.values():
            position = kin.position[point.name]
            values.update(zip(point.x, position))
            values.update(zip(point.xdot, position.diff(t)))
        return expr.subs(values)

    def moves(point) -> bool:
        return not _vanishes(at_rest(point.position.diff(t)))

    for spring in model.springs:
        if spring.damping != 0 and (moves(spring.a) or moves(spring.b)):
            return False
    for damper in model.dampers:
        if damper.coefficient != 0 and (moves(damper.a) or moves(damper.b)):
            return False
    for force in model.particle_forces:
        if force.potential is None and not _vanishes(at_rest(force.force)):
            return False
    for generalized in model.generalized_forces:
        if generalized.potential is None and not _vanishes(at_rest(generalized.force)):
            return False
    for torque in model.torques:
        if not _vanishes(at_rest(torque.torque)):
            return False
    return True


def _driven(model: Model) -> bool:
    """Whether anything but the state changes the model's energy: an input, a point that
    moves with t, or a force that reads t."""
    moves_with_t = any(model.time in sp.Matrix(point.position).free_symbols
                       for point in model.points)
    forces: list[ParticleForce | GeneralizedForce] = [*model.particle_forces,
                                                      *model.generalized_forces]
    reads_t = any(model.time in sp.Matrix([force.force]).free_symbols for force in forces)
    return bool(model.inputs) or moves_with_t or reads_t


def dissipative(model: Model, have_potential: bool) -> bool:
    """Whether E(t) - E(0) is the work of the forces that vanish at rest (dampers, friction,
    a joint spring's damping) and of nothing else, and the model has such forces: the forces
    have a potential at rest (`have_potential`, forces_have_potential's answer), nothing
    drives the model (`_driven`) and it does not conserve energy without joint limits. The
    generated struct's `dissipative`; the runtime integrates that work (dissipated_work.hpp)."""
    if not have_potential or _driven(model):
        return False
    return not conserves_energy(model, limits_stop=False)


def conserves_energy(model: Model, limits_stop: bool = True) -> bool:
    """Whether E = T + V is a constant of the motion as the model is written: every force has
    a potential (no damping, no body torques, no force without a potential), no input drives
    it, no point moves with t, and no joint limit stops it inelastically (`limits_stop`: the
    runtime enforces them). Where it is not, the plots of a run call E - E0 the energy's
    change, not an error."""
    moves_with_t = any(model.time in sp.Matrix(point.position).free_symbols
                       for point in model.points)
    # a force with a potential may still depend on velocities (a joint spring's damping) or t
    changing = {model.time, *(speed.symbol for speed in model.speeds),
                *(symbol for point in model.points for symbol in point.xdot)}
    forces: list[ParticleForce | GeneralizedForce] = [*model.particle_forces,
                                                      *model.generalized_forces]
    unbalanced = [force for force in forces
                  if force.potential is None
                  or sp.Matrix([force.force]).free_symbols & changing]
    damped = model.dampers or any(spring.damping != 0 for spring in model.springs)
    return not (damped or unbalanced or model.torques or model.inputs
                or (limits_stop and model.limits) or moves_with_t)
