# SPDX-License-Identifier: BSD-3-Clause
"""Sampled rank check of J = dX/dq: refuses coordinates that are redundant everywhere.

If J loses rank at every sampled configuration, some combination of coordinates moves no
particle (for example two angles that only appear as their sum): Mt = J^T M J is singular
everywhere and the accelerations are undefined. Rank lost only at isolated configurations
(gimbal lock, the poles of spherical coordinates) is a singularity, not a redundancy, and
is left to the runtime's conditioning checks.
"""

from __future__ import annotations

import math
import random
from typing import Callable

from gencoord.checks.conditioning import smallest_direction
from gencoord.derive.dense import Kinematics
from gencoord.errors import ModelError
from gencoord.symbolic.finite import finite_or_none
from gencoord.dsl.model import Model

SAMPLES = 24
RANK_TOLERANCE = 1e-7  # on the smallest singular value relative to the largest


def check_full_rank(model: Model, seed: int = 7, kin: Kinematics | None = None) -> list[str]:
    """Raises ModelError for coordinates redundant everywhere; returns notes for the report
    (one when J is not finite at any sample, so nothing could be checked).

    A tree of particles is checked joint by joint: J loses rank exactly where one of its
    joints' S_i does (Kinematics.numeric_joint_jacobians), and a null direction of S_i,
    zero elsewhere, is one of J. Each sample then costs O(n) instead of O(n^3)."""
    kin = kin or Kinematics(model)  # the pipeline builds it once for every stage
    evaluate: Callable[[list[float], float], list[list[list[float]]]]
    if kin.tree is None:
        blocks, jacobian = [list(range(model.nv))], kin.numeric_jacobian()

        def evaluate(q: list[float], t: float) -> list[list[list[float]]]:
            return [jacobian(q, t)]
    else:
        blocks = [node.coordinates for node in kin.tree.nodes]
        evaluate = kin.numeric_joint_jacobians()
    rng = random.Random(seed)
    unproven = {k for k, columns in enumerate(blocks) if columns}
    null_vectors: dict[int, list[float]] = {}
    evaluated = 0
    for _ in range(SAMPLES):
        values = model.on_manifold([rng.uniform(-math.pi, math.pi) for _ in model.coordinates])
        matrices = finite_or_none(evaluate, values, rng.uniform(0.0, 10.0))
        if matrices is None:
            continue  # outside the domain of X (sqrt of a negative, a pole)
        evaluated += 1
        for k in sorted(unproven):
            ratio, null_vectors[k] = smallest_direction(matrices[k])
            if ratio > RANK_TOLERANCE:
                unproven.discard(k)  # full rank somewhere: a loss of rank is a singular set
        if not unproven:
            return []
    if not evaluated:
        return [f"Rank check skipped: J = dX/dq is not finite at any of {SAMPLES} sampled "
                "configurations (q in [-pi, pi]), so redundant coordinates were not looked for"]
    block = min(unproven)
    null_vector = [0.0] * model.nv
    for j, value in zip(blocks[block], null_vectors[block]):
        null_vector[j] = value
    scale = max(abs(c) for c in null_vector)
    speeds = model.speeds  # an ordinary coordinate's speed has its name
    combination = ", ".join(f"{c.name}: {v / scale:+.3g}" for c, v in
                            zip(speeds, null_vector) if abs(v) > 1e-6 * scale)
    names = [c.name for c, v in zip(speeds, null_vector) if abs(v) > 1e-6 * scale]
    raise ModelError(
        f"the coordinates {', '.join(names)} are redundant: J = dX/dq loses rank at every one "
        f"of {evaluated} sampled configurations, because moving them together in the direction "
        f"({combination}) moves no particle, so Mt is singular everywhere. Keep one of them, "
        "or make X depend on each separately", item="coordinates",
        line=model.coordinates[0].line)
