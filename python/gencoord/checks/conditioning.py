# SPDX-License-Identifier: BSD-3-Clause
"""sigma_min / sigma_max of a sampled Jacobian J, and its near-null direction (pure Python).

Small J: Jacobi eigen-iteration on J^T J, exact to round-off. Large J (more than
JACOBI_MAX_N columns), where Jacobi's sweeps cost seconds: a Cholesky factor of J^T J, power
iteration for its largest eigenvalue and inverse iteration for its smallest, a few n^2
steps each after the n^3 / 6 factorization. A failed factorization means J^T J is singular
to working precision.
"""

from __future__ import annotations

import math

JACOBI_MAX_N = 12
ITERATIONS = 40


def smallest_direction(rows: list[list[float]]) -> tuple[float, list[float]]:
    """(sigma_min / sigma_max, the unit direction v where |J v| is smallest)."""
    return _jacobi(rows) if len(rows[0]) <= JACOBI_MAX_N else _iterative(rows)


def _jacobi(rows: list[list[float]]) -> tuple[float, list[float]]:
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


def _gram(rows: list[list[float]]) -> list[list[float]]:
    """J^T J, skipping the zeros of J (a chain's J is half zeros)."""
    n = len(rows[0])
    a = [[0.0] * n for _ in range(n)]
    for row in rows:
        nonzero = [(j, x) for j, x in enumerate(row) if x != 0.0]
        for i, xi in nonzero:
            target = a[i]
            for j, xj in nonzero:
                target[j] += xi * xj
    return a


def _cholesky(a: list[list[float]]) -> list[list[float]] | None:
    """Lower L with L L^T = a, or None where a pivot is not positive."""
    n = len(a)
    low = [[0.0] * n for _ in range(n)]
    for j in range(n):
        row_j = low[j]
        pivot = a[j][j] - sum(x * x for x in row_j[:j])
        if not pivot > 0.0:
            return None
        row_j[j] = math.sqrt(pivot)
        for i in range(j + 1, n):
            row_i = low[i]
            row_i[j] = (a[i][j] - sum(x * y for x, y in zip(row_i[:j], row_j[:j]))) / row_j[j]
    return low


def _solve(low: list[list[float]], b: list[float]) -> list[float]:
    """(L L^T)^-1 b by forward and back substitution."""
    n = len(b)
    y = [0.0] * n
    for i in range(n):
        y[i] = (b[i] - sum(low[i][k] * y[k] for k in range(i))) / low[i][i]
    x = [0.0] * n
    for i in reversed(range(n)):
        x[i] = (y[i] - sum(low[k][i] * x[k] for k in range(i + 1, n))) / low[i][i]
    return x


def solve_normal_equations(rows: list[list[float]], r: list[float],
                           damping: float) -> list[float] | None:
    """dq with (J^T J + damping I) dq = J^T r (a damped Gauss-Newton step), or None if the
    matrix is not positive definite."""
    a = _gram(rows)
    for i in range(len(a)):
        a[i][i] += damping
    low = _cholesky(a)
    if low is None:
        return None
    return _solve(low, [sum(row[i] * ri for row, ri in zip(rows, r)) for i in range(len(a))])


def least_change_step(rows: list[list[float]], residual: list[float]) -> list[float] | None:
    """The smallest dx with J dx = -residual (J's rows given), -J^T (J J^T)^-1 residual, or
    None where J has dependent rows."""
    low = _cholesky(_gram([list(column) for column in zip(*rows)]))
    if low is None:
        return None
    y = _solve(low, residual)
    return [-sum(row[j] * y[i] for i, row in enumerate(rows)) for j in range(len(rows[0]))]


def _unit(x: list[float]) -> list[float]:
    norm = math.sqrt(sum(v * v for v in x))
    return [v / norm for v in x]


def _rayleigh(a: list[list[float]], x: list[float]) -> float:
    return sum(xi * sum(r * xj for r, xj in zip(row, x)) for xi, row in zip(x, a))


def _iterative(rows: list[list[float]]) -> tuple[float, list[float]]:
    a = _gram(rows)
    n = len(a)
    start = _unit([1.0 + 0.1 * math.sin(k + 1.0) for k in range(n)])  # generic, fixed
    x = start
    for _ in range(ITERATIONS):  # power iteration: the largest eigenvalue
        x = _unit([sum(r * xj for r, xj in zip(row, x)) for row in a])
    largest = _rayleigh(a, x)
    low = _cholesky(a)
    if low is None or largest <= 0.0:
        shift = 1e-12 * max(largest, 1e-300)  # singular: the direction of a shifted inverse
        low = _cholesky([[v + shift * (i == j) for j, v in enumerate(row)]
                         for i, row in enumerate(a)])
        x = start
        if low:
            for _ in range(ITERATIONS):
                x = _unit(_solve(low, x))
        return 0.0, x
    x = start
    for _ in range(ITERATIONS):  # inverse iteration: the smallest eigenvalue
        x = _unit(_solve(low, x))
    smallest = _rayleigh(a, x)
    return math.sqrt(max(smallest, 0.0) / largest), x
