#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The peers table of scripts/bench_peers.sh: run times from bench_peers' JSON, generation and
compile times measured here.

    PYTHONHASHSEED=0 python3 bench/peers/peers_table.py --json PEERS.json --sizes "1;2;5;10;20"
        [--checks CHECKS.txt] [--eigen /usr/include/eigen3]

Run times are Google Benchmark's CPU time per call (single-threaded kernels; on a shared machine
CPU time is disturbed less than wall time), except the batches, which are wall time; with
--benchmark_repetitions=N, the fastest repetition of each.
Generation and compile times are CPU seconds (user + sys) of the child processes:
  ours       PYTHONHASHSEED=0 ./generate models/n_link_chain.py --set n=N -o TMP --quiet
             (the whole process: imports, checks and analyses included)
  SymPy      bench/peers/sympy_chain_peer.py N: its own Kane and cse+print CPU times
             (after `import sympy`)
  compile    g++ -std=c++17 -O2 -c on a file that includes the header and calls qddot
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def child_cpu(command, **kwargs):
    """Runs command; returns (CPU seconds of it and its children, its stdout)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(command, check=True, capture_output=True, text=True, **kwargs).stdout
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), out


def compile_cpu(source, include_dirs, folder):
    path = os.path.join(folder, "tu.cc")
    with open(path, "w") as f:
        f.write(source)
    flags = [f"-I{d}" for d in include_dirs]
    seconds, _ = child_cpu(["g++", "-std=c++17", "-O2", *flags, "-c", path,
                            "-o", os.path.join(folder, "tu.o")])
    return seconds


OURS_TU = """#include "generated/n_link_chain_{n}.hpp"
using M = gencoord::models::NLinkChain{n};
M::QVector<double> qddot(const M::QVector<double>& q, const M::QVector<double>& v,
                         const M::Params& p) {{ return M::qddot(q, v, 0.0, p); }}
"""
SYMPY_TU = """#include "peers/sympy_chain_{n}.hpp"
void qddot(const double* q, const double* u, const double* p, double* out) {{
  peers::SympyChain{n}::qddot(q, u, p, out);
}}
"""


def generation_and_compile(n, eigen, sympy_max_n):
    """CPU seconds: ours generate, SymPy Kane, SymPy cse+print, ours compile, SymPy compile
    (None for the SymPy peer past sympy_max_n)."""
    with tempfile.TemporaryDirectory() as tmp:
        ours_dir = os.path.join(tmp, "generated")
        ours_gen, _ = child_cpu([sys.executable, os.path.join(ROOT, "generate"),
                                 "models/n_link_chain.py", "--set", f"n={n}", "-o", ours_dir,
                                 "--quiet"], cwd=ROOT, env=dict(os.environ, PYTHONHASHSEED="0"))
        ours_cc = compile_cpu(OURS_TU.format(n=n), [tmp, eigen], tmp)
        if n > sympy_max_n:
            return ours_gen, None, None, ours_cc, None
        os.makedirs(os.path.join(tmp, "peers"))
        _, printed = child_cpu([sys.executable,
                                os.path.join(ROOT, "bench", "peers", "sympy_chain_peer.py"),
                                str(n), os.path.join(tmp, "peers", f"sympy_chain_{n}.hpp")],
                               env=dict(os.environ, PYTHONHASHSEED="0"))
        times = dict(line.split() for line in printed.splitlines())
        sympy_cc = compile_cpu(SYMPY_TU.format(n=n), [tmp, eigen], tmp)
    return (ours_gen, float(times["kane_cpu_s"]), float(times["cse_print_cpu_s"]), ours_cc,
            sympy_cc)


def fmt(x, digits=3):
    if x is None:
        return "–"
    return f"{x:.{digits}g}" if x < 1000 else f"{x:.0f}"


def ratio(a, b):
    return None if a is None or b is None else a / b


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", required=True, help="bench_peers --benchmark_out file")
    parser.add_argument("--sizes", default="1;2;5;10;20", help="chain sizes, ';'-separated")
    parser.add_argument("--checks", help="bench_peers' stderr, for its cross-check lines")
    parser.add_argument("--sympy-max-n", type=int, default=20,
                        help="largest chain with a SymPy peer (GENCOORD_SYMPY_PEER_MAX_N)")
    parser.add_argument("--eigen", default="/usr/include/eigen3", help="Eigen include folder")
    args = parser.parse_args()

    with open(args.json) as f:
        report = json.load(f)
    # with --benchmark_repetitions, the fastest repetition: what the code costs when nothing
    # else on the machine gets in the way
    cpu, real = {}, {}
    for b in report["benchmarks"]:
        if b.get("run_type", "iteration") != "iteration":
            continue
        name = b.get("run_name", b["name"])
        # ns: bench_peers keeps the default time unit
        cpu[name] = min(cpu.get(name, float("inf")), b["cpu_time"])
        real[name] = min(real.get(name, float("inf")), b["real_time"])
    sizes = [int(s) for s in args.sizes.replace(",", ";").split(";") if s]
    context = report["context"]
    print(f"\nbench_peers on {context.get('num_cpus')} CPUs at "
          f"{context.get('mhz_per_cpu')} MHz, load average {context.get('load_avg')}; "
          "times in CPU ns per call, generation and compile in CPU s\n")
    print("| n | ours ns/qddot | SymPy ns/qddot | MuJoCo ns/mj_forward | SymPy/ours | "
          "MuJoCo/ours | ours ns/RK4 step | SymPy ns/RK4 step | ours generate s | "
          "SymPy Kane s | SymPy Kane+cse+print s | ours compile -O2 s | SymPy compile -O2 s |")
    print("|" + " --- |" * 13)
    for n in sizes:
        ours, sym, mj = (cpu.get(f"qddot/ours/{n}"), cpu.get(f"qddot/sympy/{n}"),
                         cpu.get(f"mj_forward/{n}"))
        ours_rk4, sym_rk4 = cpu.get(f"rk4_step/ours/{n}"), cpu.get(f"rk4_step/sympy/{n}")
        gen, kane, cse_print, ours_cc, sym_cc = generation_and_compile(n, args.eigen,
                                                                       args.sympy_max_n)
        kane_total = None if kane is None else kane + cse_print
        cells = [n, fmt(ours), fmt(sym), fmt(mj), fmt(ratio(sym, ours), 2),
                 fmt(ratio(mj, ours), 2), fmt(ours_rk4), fmt(sym_rk4), fmt(gen), fmt(kane),
                 fmt(kane_total), fmt(ours_cc), fmt(sym_cc)]
        print("| " + " | ".join(str(c) for c in cells) + " |", flush=True)

    print("\nBatched (gencoord/parallel/batch.hpp, 4096 states, wall ns per state; "
          "speedup = 1 thread / 2 threads)\n")
    print("| n | qddot 1 thread | qddot 2 threads | speedup | RK4 1 thread | RK4 2 threads | "
          "speedup |")
    print("|" + " --- |" * 7)
    for n in sizes:
        cells = [n]
        for kind in ("qddot", "rk4"):
            one = real.get(f"batch_{kind}/ours/{n}/threads:1/real_time")
            two = real.get(f"batch_{kind}/ours/{n}/threads:2/real_time")
            per = [None if t is None else t / 4096 for t in (one, two)]
            cells += [fmt(per[0]), fmt(per[1]), fmt(ratio(one, two), 2)]
        print("| " + " | ".join(str(c) for c in cells) + " |")

    if args.checks and os.path.exists(args.checks):
        print("\nCross-checks against ours (before timing):")
        with open(args.checks) as f:
            for line in f:
                if line.startswith("check "):
                    print("  " + line.rstrip())


if __name__ == "__main__":
    main()
