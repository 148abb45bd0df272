# SPDX-License-Identifier: BSD-3-Clause
"""The samples of a sweep, in their fixed order: one row of values per sample, one value per
variable (q, then v, then parameters, each in the file's order).

- grid: every combination of the variables' points; the first variable varies slowest.
- monte_carlo: Python's `random.Random(seed)` (the Mersenne Twister; `random()` of an integer
  seed gives the same numbers in every Python version); sample by sample, variable by
  variable, x = from + (to - from) u with u = random().
- latin_hypercube: for each variable in turn, a random permutation p of 0..n-1 (Fisher-Yates
  from the end: for i = n-1 down to 1, swap i with floor(random() (i + 1))) and then, for
  each sample i, u = (p[i] + random()) / n and x = from + (to - from) u: each of the n
  strata of every variable holds one sample.
Only `random()` is used, because it is the one draw whose sequence Python guarantees."""

from __future__ import annotations

import itertools
import random
from collections.abc import Iterator

from gencoord.sweep.spec import Sweep


def _latin_hypercube(sweep: Sweep) -> list[list[float]]:
    rng = random.Random(sweep.seed)
    n = sweep.count
    columns = []
    for variable in sweep.variables:
        order = list(range(n))
        for i in range(n - 1, 0, -1):
            j = int(rng.random() * (i + 1))
            order[i], order[j] = order[j], order[i]
        span = variable.high - variable.low
        columns.append([variable.low + span * ((order[i] + rng.random()) / n)
                        for i in range(n)])
    return columns


def rows(sweep: Sweep) -> Iterator[tuple[float, ...]]:
    """The samples' values, sample by sample."""
    if sweep.method == "grid":
        yield from itertools.product(*(v.values for v in sweep.variables))
    elif sweep.method == "monte_carlo":
        rng = random.Random(sweep.seed)
        for _ in range(sweep.count):
            yield tuple(v.low + (v.high - v.low) * rng.random() for v in sweep.variables)
    else:
        yield from zip(*_latin_hypercube(sweep))
