# SPDX-License-Identifier: BSD-3-Clause
"""Redundancy within the sampled domain: distinct q that put every particle in the same place.

Spherical coordinates map (theta, phi) and (-theta, phi + pi) to the same point; Z-Y-X Euler
angles map (yaw, pitch, roll) and (yaw + pi, pi - pitch, roll + pi) to the same orientation.
That is not an error (the dynamics are fine in either branch), but it matters to anyone who
maps positions back to coordinates (the inverse map, an atlas) or compares coordinates: the
branch depends on the first guess. The search: for a few random targets q1, Gauss-Newton on
X(q) = X(q1) from random starts in [-pi, pi]^nq; a solution q2 that differs from q1 by more
than whole turns of 2 pi is reported as a warning.
"""

from __future__ import annotations

import math
import random

import sympy as sp

from gencoord.checks.budget import Budget
from gencoord.checks.conditioning import solve_normal_equations
from gencoord.derive.dense import Kinematics
from gencoord.symbolic.finite import finite_or_none
from gencoord.dsl.model import Model

MAX_NQ = 6          # pure-Python Gauss-Newton: cheap up to here, skipped beyond
TARGETS = 6
STARTS = 6
ITERATIONS = 40
SEARCH_SECONDS = 0.4  # CPU budget of the whole search
TIME = 0.7          # the instant the positions are compared at (time-dependent models)


def _gauss_newton(position, jacobian, target: list[float], q: list[float]) -> list[float] | None:
    """A q with X(q) = target from the start q (damped Gauss-Newton), or None (also when X or
    J is not finite along the way: the iteration left the domain of X)."""
    scale = 1.0 + max(abs(x) for x in target)
    damping = 1e-3
    x = position(q)
    if x is None:
        return None
    r = [a - b for a, b in zip(target, x)]
    norm = math.sqrt(sum(v * v for v in r))
    for _ in range(ITERATIONS):
        if norm < 1e-11 * scale:
            return q
        matrix = jacobian(q)
        step = None if matrix is None else solve_normal_equations(matrix, r, damping)
        if step is None:
            return None
        trial = [a + b for a, b in zip(q, step)]
        x = position(trial)
        if x is None:  # outside the domain of X: a shorter step
            damping *= 10.0
            continue
        trial_r = [a - b for a, b in zip(target, x)]
        trial_norm = math.sqrt(sum(v * v for v in trial_r))
        if trial_norm < norm:
            q, r, norm, damping = trial, trial_r, trial_norm, max(damping * 0.3, 1e-12)
        else:
            damping *= 10.0
    return None


def _beyond_whole_turns(q1: list[float], q2: list[float]) -> bool:
    """Whether q2 - q1 is more than a multiple of 2 pi in some coordinate."""
    for a, b in zip(q1, q2):
        d = math.remainder(b - a, 2.0 * math.pi)
        if abs(d) > 1e-5:
            return True
    return False


def find_redundancy(model: Model, kin: Kinematics, seed: int = 5,
                    notes: list[str] | None = None) -> str | None:
    """A warning line naming two distinct configurations with the same positions, or None.

    Appends a line to `notes` when the search stops at its time budget."""
    q = [c.symbol for c in model.coordinates]
    if len(q) > MAX_NQ:
        return None
    x = sp.Matrix.vstack(*[kin.position[p.name] for p in model.particles])
    x_function = sp.lambdify([q], list(x.xreplace(kin.defaults).subs(kin.t, TIME)),
                             modules="math")
    numeric_jacobian = kin.numeric_jacobian()  # compiled once, shared with the other checks

    def position(values):
        return finite_or_none(lambda: [float(v) for v in x_function(values)])

    def jacobian(values):
        return finite_or_none(numeric_jacobian, values, TIME)

    rng = random.Random(seed)
    budget = Budget(SEARCH_SECONDS)
    for _ in range(TARGETS):
        q1 = [rng.uniform(-math.pi, math.pi) for _ in q]
        target = position(q1)
        if target is None:
            continue
        for _ in range(STARTS):
            if budget.spent():
                if notes is not None:
                    notes.append(f"Redundancy search stopped at its time budget "
                                 f"({SEARCH_SECONDS:g} s CPU)")
                return None
            q2 = _gauss_newton(position, jacobian, target,
                               [rng.uniform(-math.pi, math.pi) for _ in q])
            if q2 is not None and _beyond_whole_turns(q1, q2):
                def show(values):
                    return ", ".join(f"{c.name} = {v:.4g}"
                                     for c, v in zip(model.coordinates, values))
                return (f"Redundancy (warning): distinct coordinates give the same positions, "
                        f"e.g. {show(q1)} and {show(q2)}; mapping positions back to q (the "
                        f"inverse map, an atlas) depends on the first guess")
    return None
