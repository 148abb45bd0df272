# SPDX-License-Identifier: BSD-3-Clause
"""Compile time of a whole generated n-link chain at -O2: every kernel, reduced and maximal.

    PYTHONHASHSEED=0 python3 bench/compile_time.py --n 50 --translation-units 4 --jobs 2

Generates models/n_link_chain.py at size n into a temporary folder (header only, or with
--translation-units K the header and its K <name>_double_k.cpp files), writes one more file
that includes the header and calls every kernel with double (what an application using the
whole model compiles), and compiles all of them with `g++ -std=c++17 -O2 -DNDEBUG`, at most
--jobs at a time, as `make -j` would. Prints each file's CPU seconds and peak memory, then the
wall time of the whole build and its CPU time (user + sys of the compilers).
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Calls every kernel of the chain with double, so no kernel is left out of the measurement.
USER_FILE = """\
#include "n_link_chain_{n}.hpp"
using M = gencoord::models::NLinkChain{n};
using X = M::Maximal;
double touch_all(const M::QVector<double>& q, const M::QVector<double>& v, const M::Params& p,
                 const M::XVector<double>& x, const M::XVector<double>& xd) {{
  double t = 0, kappa = 1e4, damping = 1.0, s = 0;
  M::QMatrix<double> a, b;
  M::QVector<double> f;
  s += M::mass_matrix(q, t, p).sum() + M::applied_forces(q, v, t, p).sum();
  s += M::generalized_forces(q, v, t, p).sum() + M::inertial_forces(q, v, t, p).sum();
  s += M::forces(q, v, t, p).sum();
  M::dynamics(q, v, t, p, &a, &f); s += a.sum() + f.sum();
  s += M::inverse_dynamics(q, v, q, t, p).sum();
  M::residual_jacobians(q, v, q, t, p, &a, &b); s += a.sum() + b.sum();
  s += M::kinetic_energy(q, v, t, p) + M::potential_energy(q, t, p) +
       M::generalized_potential_energy(q, t, p) + M::energy(q, v, t, p);
  s += M::positions(q, t, p).sum() + M::velocities(q, v, t, p).sum();
  s += M::jacobian(q, t, p).sum() + M::bias_acceleration(q, v, t, p).sum();
  s += M::linear_momentum(q, v, t, p).sum() + M::angular_momentum(q, v, t, p).sum();
  s += M::particle_masses<double>(p).sum() + M::qddot(q, v, t, p).sum();
  s += X::external_forces(x, xd, t, p).sum();
  s += X::penalty_forces(x, xd, t, kappa, damping, p).sum();
  s += X::force_jacobian_x(x, xd, t, kappa, damping, p)[3];
  s += X::force_jacobian_xdot(x, xd, t, kappa, damping, p)[5];
  s += X::potential_energy(x, t, p) + X::penalty_energy(x, t, kappa, p);
  s += X::constraint_violations(x, t, p).sum();
  return s;
}}
"""


def compile_one(source: str, folder: str, eigen: str) -> tuple[str, float, int]:
    """Compiles `source`; returns (name, CPU seconds, peak memory in MiB)."""
    command = ["/usr/bin/time", "-f", "%U %S %M", "g++", "-std=c++17", "-O2", "-DNDEBUG",
               f"-I{folder}", f"-I{eigen}", "-c", source, "-o", source + ".o"]
    result = subprocess.run(command, capture_output=True, text=True, cwd=folder)
    if result.returncode != 0:
        sys.exit(f"compile_time: g++ failed on {source}:\n{result.stderr[-4000:]}")
    user, system, peak_kib = result.stderr.strip().splitlines()[-1].split()
    return os.path.basename(source), float(user) + float(system), int(peak_kib) // 1024


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=50, help="links of the chain (default 50)")
    parser.add_argument("--translation-units", type=int, default=0, metavar="K",
                        help="generate with --translation-units K (default 0: header only)")
    parser.add_argument("--max-function-statements", type=int, default=None, metavar="N",
                        help="passed to ./generate (default: its own default)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                        help="files compiled at once (default: the number of cores)")
    parser.add_argument("--eigen", default="/usr/include/eigen3")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory(prefix="gencoord-compile-") as folder:
        command = [sys.executable, os.path.join(ROOT, "generate"), "-q",
                   os.path.join(ROOT, "models", "n_link_chain.py"), "--set", f"n={args.n}",
                   "-o", folder, "--translation-units", str(args.translation_units),
                   "--maximal"]
        if args.max_function_statements is not None:
            command += ["--max-function-statements", str(args.max_function_statements)]
        started = time.perf_counter()
        subprocess.run(command, check=True, env=dict(os.environ, PYTHONHASHSEED="0"))
        generation = time.perf_counter() - started
        user_file = os.path.join(folder, "uses_every_kernel.cpp")
        with open(user_file, "w", encoding="utf-8") as handle:
            handle.write(USER_FILE.format(n=args.n))
        sources = sorted(os.path.join(folder, f) for f in os.listdir(folder)
                         if f.endswith(".cpp"))
        # the largest files first, as a build tool that knows them would schedule
        sources.sort(key=lambda path: -os.path.getsize(path))
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        started = time.perf_counter()
        with ThreadPoolExecutor(max_workers=args.jobs) as pool:
            results = list(pool.map(lambda s: compile_one(s, folder, args.eigen), sources))
        wall = time.perf_counter() - started
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    print(f"n = {args.n}, --translation-units {args.translation_units}, "
          f"--max-function-statements {args.max_function_statements or 'default'}, "
          f"{args.jobs} jobs (generation {generation:.1f} s wall)")
    for name, seconds, peak in sorted(results):
        print(f"  {name:<40} {seconds:7.1f} s CPU {peak:6d} MiB")
    print(f"compile: {wall:.1f} s wall, {cpu:.1f} s CPU")


if __name__ == "__main__":
    main()
