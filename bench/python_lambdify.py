#!/usr/bin/env python3
"""qddot of the planar n-link chain from Python: the model's gencoord module against the
route users of sympy.physics.mechanics take, lambdify of the mass matrix M and forcing f of
LagrangesMethod, then numpy.linalg.solve(M, f).

Both contenders run interleaved in one process pinned to one core, on the same random states;
each round times one call per state (single calls) and one batch of all states (the module's
batch on one thread against a Python loop over the lambdified functions). Prints the minimum
and the median per state over the rounds and the ratios. Run with a Python that has NumPy and
SymPy (Debian's /usr/bin/python3):

    /usr/bin/python3 bench/python_lambdify.py [--sizes 2,5] [--batch 10000] [--rounds 7]
"""

from __future__ import annotations

import argparse
import importlib
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
import sympy as sp
from sympy.physics import mechanics as me

REPOSITORY = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def lambdified_chain(n: int):
    """qddot(q, u) of the chain of n unit links and unit masses, g = 9.81, through
    LagrangesMethod and lambdify: the defaults of models/n_link_chain.py."""
    q = me.dynamicsymbols(f"q1:{n + 1}")
    qd = [me.dynamicsymbols(f"q{k + 1}", 1) for k in range(n)]
    frame, origin = me.ReferenceFrame("N"), me.Point("O")
    origin.set_vel(frame, 0)
    particles, point = [], origin
    for k in range(n):
        point = point.locatenew(f"P{k}", sp.sin(q[k]) * frame.x - sp.cos(q[k]) * frame.y)
        point.set_vel(frame, point.pos_from(origin).dt(frame))
        particle = me.Particle(f"p{k}", point, 1)
        particle.potential_energy = 9.81 * point.pos_from(origin).dot(frame.y)
        particles.append(particle)
    method = me.LagrangesMethod(me.Lagrangian(frame, *particles), q)
    method.form_lagranges_equations()
    u = sp.symbols(f"u1:{n + 1}")
    values = dict(zip(qd, u))
    mass = sp.lambdify([q, u], method.mass_matrix.subs(values), "numpy")
    forcing = sp.lambdify([q, u], method.forcing.subs(values), "numpy")
    return lambda qs, us: np.linalg.solve(mass(qs, us), forcing(qs, us).ravel())


def chain_module(n: int, folder: str):
    """The module of models/n_link_chain.py with n links, built by `gencoord python`."""
    subprocess.run([os.path.join(REPOSITORY, "gencoord"), "python",
                    os.path.join(REPOSITORY, "models", "n_link_chain.py"), "--set", f"n={n}",
                    "--python", sys.executable, "-o", folder], check=True,
                   stdout=subprocess.DEVNULL)
    sys.path.insert(0, folder)
    return importlib.import_module(f"n_link_chain_{n}")


def per_state(seconds: list[float], count: int) -> tuple[float, float]:
    return min(seconds) / count, statistics.median(seconds) / count


def measure(n: int, batch: int, rounds: int, folder: str) -> None:
    module, solve = chain_module(n, folder), lambdified_chain(n)
    rng = np.random.default_rng(n)
    q, v = rng.uniform(-1, 1, (batch, n)), rng.uniform(-1, 1, (batch, n))
    worst = np.abs(module.qddot(q[:100], v[:100]) -
                   np.array([solve(q[i], v[i]) for i in range(100)])).max()
    singles = min(batch, 1000)
    times = {name: [] for name in ("module", "lambdify", "module batch", "lambdify loop")}
    for _ in range(rounds):
        start = time.perf_counter()
        for i in range(singles):
            module.qddot(q[i], v[i])
        times["module"].append(time.perf_counter() - start)
        start = time.perf_counter()
        for i in range(singles):
            solve(q[i], v[i])
        times["lambdify"].append(time.perf_counter() - start)
        start = time.perf_counter()
        module.qddot(q, v, threads=1)
        times["module batch"].append(time.perf_counter() - start)
        start = time.perf_counter()
        for i in range(batch):
            solve(q[i], v[i])
        times["lambdify loop"].append(time.perf_counter() - start)
    print(f"n = {n}: {singles} single calls and a batch of {batch} states, {rounds} rounds; "
          f"largest difference {worst:.1e}")
    print(f"  {'contender':<16}{'min (us/state)':>16}{'median':>10}")
    results = {}
    for name, seconds in times.items():
        count = singles if name in ("module", "lambdify") else batch
        results[name] = per_state(seconds, count)
        print(f"  {name:<16}{results[name][0] * 1e6:>16.3f}{results[name][1] * 1e6:>10.3f}")
    for fast, slow in (("module", "lambdify"), ("module batch", "lambdify loop")):
        print(f"  {slow} / {fast}: {results[slow][0] / results[fast][0]:.1f}x (min), "
              f"{results[slow][1] / results[fast][1]:.1f}x (median)")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", default="2,5", help="chain lengths (default 2,5)")
    parser.add_argument("--batch", type=int, default=10000, help="states per batch")
    parser.add_argument("--rounds", type=int, default=7, help="timed rounds")
    args = parser.parse_args()
    os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
    with tempfile.TemporaryDirectory(prefix="gencoord-bench-") as folder:
        for n in (int(size) for size in args.sizes.split(",")):
            measure(n, args.batch, args.rounds, folder)
    return 0


if __name__ == "__main__":
    sys.exit(main())
