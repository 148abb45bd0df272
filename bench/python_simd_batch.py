#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""A model module's qddot batch on one thread against qddot_simd, which evaluates the same
batch four states per kernel call across SIMD lanes (the generated qddot instantiated with
Pack<4>, built with -mavx2 -mfma where the machine has them).

Both run interleaved in one process pinned to one core, on the same random states (unit
quaternions where the model has them), threads=1; prints the minimum and the median per state
over the rounds, their ratio and the largest relative difference between the two. The modules
are built as `gencoord python` builds them, into the per-user cache. Run with a Python that has
NumPy (Debian's /usr/bin/python3):

    /usr/bin/python3 bench/python_simd_batch.py [--models chain10,iiwa14,floating_quadruped]
                                                 [--batch 4096] [--rounds 15]
"""

from __future__ import annotations

import argparse
import importlib
import os
import statistics
import sys
import time

import numpy as np

REPOSITORY = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPOSITORY, "python"))

from gencoord.tool.driver_build import python_module  # noqa: E402
from gencoord.tool.layout import find_layout  # noqa: E402
from gencoord.tool.model_file import load  # noqa: E402

MODELS = {  # name: (model file, settings)
    "chain10": ("models/n_link_chain.py", {"n": "10"}),
    "iiwa14": ("models/iiwa14.urdf", {}),
    "floating_quadruped": ("models/floating_quadruped.urdf", {}),
}


def module_of(name: str):
    path, settings = MODELS[name]
    target = load(os.path.join(REPOSITORY, path), settings).target
    built = python_module(find_layout(), target, sys.executable)
    sys.path.insert(0, os.path.dirname(built))
    return importlib.import_module(target.name)


def random_states(module, count: int):
    rng = np.random.default_rng(7)
    q = module.initial_q + rng.uniform(-1, 1, (count, module.nq))
    for start in module.quaternion_starts:
        q[:, start:start + 4] /= np.linalg.norm(q[:, start:start + 4], axis=1)[:, None]
    return q, rng.uniform(-1, 1, (count, module.nv)), rng.uniform(0, 1, count)


def measure(name: str, batch: int, rounds: int) -> None:
    module = module_of(name)
    q, v, t = random_states(module, batch)
    scalar, packed = module.qddot(q, v, t, threads=1), module.qddot_simd(q, v, t, threads=1)
    scale = np.maximum(1.0, np.linalg.norm(scalar, axis=1))[:, None]
    worst = np.max(np.abs(packed - scalar) / scale)
    times = {"qddot": [], "qddot_simd": []}
    for _ in range(rounds):
        for contender, seconds in times.items():
            kernel = getattr(module, contender)
            start = time.perf_counter()
            kernel(q, v, t, threads=1)
            seconds.append(time.perf_counter() - start)
    print(f"{name} (nq = {module.nq}, nv = {module.nv}): a batch of {batch} states, {rounds} "
          f"rounds; largest relative difference {worst:.1e}")
    print(f"  {'contender':<12}{'min (ns/state)':>16}{'median':>10}")
    results = {}
    for contender, seconds in times.items():
        results[contender] = (min(seconds) / batch, statistics.median(seconds) / batch)
        print(f"  {contender:<12}{results[contender][0] * 1e9:>16.1f}"
              f"{results[contender][1] * 1e9:>10.1f}")
    ratio = [results["qddot"][k] / results["qddot_simd"][k] for k in (0, 1)]
    print(f"  qddot / qddot_simd: {ratio[0]:.2f}x (min), {ratio[1]:.2f}x (median)")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--models", default=",".join(MODELS),
                        help=f"comma-separated, of {', '.join(MODELS)} (default: all)")
    parser.add_argument("--batch", type=int, default=4096, help="states per batch")
    parser.add_argument("--rounds", type=int, default=15, help="timed rounds")
    args = parser.parse_args()
    names = args.models.split(",")
    unknown = [n for n in names if n not in MODELS]
    if unknown:
        parser.error(f"--models: unknown {', '.join(unknown)}; known: {', '.join(MODELS)}")
    os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
    for name in names:
        measure(name, args.batch, args.rounds)
    return 0


if __name__ == "__main__":
    sys.exit(main())
