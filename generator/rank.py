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

import sympy as sp

from .derive import Kinematics
from .errors import ModelError
from .model import Model

SAMPLES = 24
RANK_TOLERANCE = 1e-7  # on the smallest singular value relative to the largest


def _smallest_direction(rows: list[list[float]]) -> tuple[float, list[float]]:
    """(sigma_min / sigma_max, the unit null-ish direction) of a tall matrix J.

    Pure Python (no numpy here): Jacobi eigen-iteration on the small n x n matrix J^T J.
    """
    n = len(rows[0])
    a = [[sum(r[i] * r[j] for r in rows) for j in range(n)] for i in range(n)]
    vectors = [[float(i == j) for j in range(n)] for i in range(n)]
    for _ in range(60):
        off = sum(a[i][j] ** 2 for i in range(n) for j in range(n) if i != j)
        if off <= 1e-30 * sum(a[i][i] ** 2 for i in range(n)):
            break
        for p in range(n):
            for q in range(p + 1, n):
                if a[p][q] == 0.0:
                    continue
                theta = (a[q][q] - a[p][p]) / (2 * a[p][q])
                t = math.copysign(1.0, theta) / (abs(theta) + math.sqrt(theta * theta + 1))
                c = 1 / math.sqrt(t * t + 1)
                s_ = t * c
                for k in range(n):  # rotate columns p, q
                    akp, akq = a[k][p], a[k][q]
                    a[k][p], a[k][q] = c * akp - s_ * akq, s_ * akp + c * akq
                for k in range(n):  # rotate rows p, q
                    apk, aqk = a[p][k], a[q][k]
                    a[p][k], a[q][k] = c * apk - s_ * aqk, s_ * apk + c * aqk
                for k in range(n):
                    vkp, vkq = vectors[k][p], vectors[k][q]
                    vectors[k][p], vectors[k][q] = c * vkp - s_ * vkq, s_ * vkp + c * vkq
    eigenvalues = [a[i][i] for i in range(n)]
    smallest = min(range(n), key=lambda i: eigenvalues[i])
    largest = max(eigenvalues)
    ratio = math.sqrt(max(eigenvalues[smallest], 0.0) / largest) if largest > 0 else 0.0
    return ratio, [vectors[k][smallest] for k in range(n)]


def check_full_rank(model: Model, seed: int = 7, kin: Kinematics | None = None) -> None:
    kin = kin or Kinematics(model)  # the pipeline builds it once for every stage
    q = [c.symbol for c in model.coordinates]
    jacobian = sp.Matrix.vstack(*[kin.jacobian[p.name] for p in model.particles])
    defaults = {p.symbol: sp.Float(p.default) for p in model.parameters}
    evaluate = sp.lambdify([q, kin.t], jacobian.xreplace(defaults).tolist(), modules="math")
    rng = random.Random(seed)
    null_vector = None
    for _ in range(SAMPLES):
        values = [rng.uniform(-math.pi, math.pi) for _ in q]
        J = [[float(x) for x in row] for row in evaluate(values, rng.uniform(0.0, 10.0))]
        ratio, null_vector = _smallest_direction(J)
        if ratio > RANK_TOLERANCE:
            return  # full rank somewhere: any loss of rank is a singular set, not redundancy
    scale = max(abs(c) for c in null_vector)
    combination = ", ".join(f"{c.name}: {v / scale:+.3g}" for c, v in
                            zip(model.coordinates, null_vector) if abs(v) > 1e-6 * scale)
    names = [c.name for c, v in zip(model.coordinates, null_vector) if abs(v) > 1e-6 * scale]
    raise ModelError(
        f"the coordinates {', '.join(names)} are redundant: J = dX/dq loses rank at every one "
        f"of {SAMPLES} sampled configurations, because moving them together in the direction "
        f"({combination}) moves no particle, so Mt is singular everywhere. Keep one of them, "
        "or make X depend on each separately", item="coordinates",
        line=model.coordinates[0].line)
