#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""qddot of the planar n-link chain from Python: the model's gencoord module against the
route users of sympy.physics.mechanics take, lambdify of the mass matrix M and forcing f of
LagrangesMethod, then numpy.linalg.solve(M, f).

Every contender runs interleaved in one process pinned to one core, on the same random states;
each round times one call per state (single calls) and one batch of all states (the module's
batch on one thread against a Python loop over the lambdified functions). Beside them, the
floor of a single call (bench/python_call_floor.cpp, compiled with the module's own compile
command): the same C++ kernel called from C++, and an empty pybind11 function with qddot's
signature, whose sum is what one call from Python cannot go below. Prints the minimum and the
median per state over the rounds and the ratios. Run with a Python that has NumPy and SymPy
(Debian's /usr/bin/python3):

    /usr/bin/python3 bench/python_lambdify.py [--sizes 2,5] [--batch 10000] [--rounds 7]
"""

from __future__ import annotations

import argparse
import importlib
import json
import os
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
import sympy as sp
from sympy.physics import mechanics as me

REPOSITORY = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPOSITORY, "python"))

from gencoord.tool.driver_build import python_module  # noqa: E402
from gencoord.tool.layout import find_layout  # noqa: E402
from gencoord.tool.model_file import load  # noqa: E402

FLOOR_SOURCE = os.path.join(REPOSITORY, "bench", "python_call_floor.cpp")


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


def chain_modules(n: int, folder: str):
    """The module of models/n_link_chain.py with n links (built as `gencoord python` builds
    it, into the cache) and its floor module, compiled into `folder` with the module's compile
    command, the source swapped."""
    target = load(os.path.join(REPOSITORY, "models", "n_link_chain.py"), {"n": str(n)}).target
    built = python_module(find_layout(), target, sys.executable)
    with open(os.path.join(os.path.dirname(built), "compile_commands.json"),
              encoding="utf-8") as handle:
        entry = next(e for e in json.load(handle) if e["file"].endswith("model_module.cpp"))
    floor_name = f"floor_{target.name}"
    words = shlex.split(entry["command"])
    source_at, output_at = words.index(entry["file"]), words.index("-o") + 1
    words[source_at], words[output_at] = FLOOR_SOURCE, os.path.join(folder, floor_name + ".o")
    words = [f"-DGENCOORD_MODULE_NAME={floor_name}" if w.startswith("-DGENCOORD_MODULE_NAME=")
             else w for w in words]
    suffix = os.path.basename(built)[len(target.name):]  # e.g. .cpython-311-x86_64-linux-gnu.so
    for command in (words, [words[0], "-shared", words[output_at], "-o",
                            os.path.join(folder, floor_name + suffix)]):
        subprocess.run(command, check=True, cwd=entry["directory"])
    shutil.copy(built, folder)
    sys.path.insert(0, folder)
    return importlib.import_module(target.name), importlib.import_module(floor_name)


def per_state(seconds: list[float], count: int) -> tuple[float, float]:
    return min(seconds) / count, statistics.median(seconds) / count


def measure(n: int, batch: int, rounds: int, folder: str) -> None:
    (module, floor), solve = chain_modules(n, folder), lambdified_chain(n)
    rng = np.random.default_rng(n)
    q, v = rng.uniform(-1, 1, (batch, n)), rng.uniform(-1, 1, (batch, n))
    worst = np.abs(module.qddot(q[:100], v[:100]) -
                   np.array([solve(q[i], v[i]) for i in range(100)])).max()
    singles = min(batch, 1000)
    names = ("module", "bare C++", "empty call", "lambdify", "module batch", "lambdify loop")
    times = {name: [] for name in names}
    for _ in range(rounds):
        start = time.perf_counter()
        for i in range(singles):
            module.qddot(q[i], v[i])
        times["module"].append(time.perf_counter() - start)
        times["bare C++"].append(floor.bare_qddot(q[:singles], v[:singles])[0])
        start = time.perf_counter()
        for i in range(singles):
            floor.empty(q[i], v[i])
        times["empty call"].append(time.perf_counter() - start)
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
        count = batch if name in ("module batch", "lambdify loop") else singles
        results[name] = per_state(seconds, count)
        print(f"  {name:<16}{results[name][0] * 1e6:>16.3f}{results[name][1] * 1e6:>10.3f}")
    floor_of = [results["bare C++"][k] + results["empty call"][k] for k in (0, 1)]
    print(f"  module / (bare C++ + empty call): {results['module'][0] / floor_of[0]:.2f}x (min), "
          f"{results['module'][1] / floor_of[1]:.2f}x (median)")
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
