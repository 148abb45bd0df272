#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Generation time (load, check, derive, CSE, emit) of every built-in model, and peak memory.

    PYTHONHASHSEED=0 python3 bench/generation_time.py [MODEL ...] [--chain 10,20,50] [--repeat 3]

Without MODEL arguments the built-in models are measured: gencoord/tool/model_list.py's,
benchmark variants included (models/ and models/variants.txt). MODEL arguments (model files or
URDFs, e.g. models/iiwa14.urdf) replace them. --chain adds planar chains (models/n_link_chain.py)
of the sizes given, --chain-only leaves out every other model.

Each model is generated in a fresh process (as the build does), into a temporary folder,
`--repeat` times; the fastest run is shown. Columns: derive + CSE + emit (what
docs/performance.md calls generation, as `./generate -v` times them), the whole process's CPU
time (Python start-up, SymPy import and the checks included) and its wall time.
"""
import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
from gencoord.tool.model_list import variants  # noqa: E402

GENERATION_STAGES = ("derive", "optimize (CSE)", "emit")
_STAGE_LINE = re.compile(r"^\s+(.+?)\s+([0-9.]+) s$")


def measure(arguments, output):
    """(derive + CSE + emit seconds, CPU seconds, wall seconds) of one `./generate -v` run."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    child = subprocess.run([sys.executable, os.path.join(ROOT, "generate"), *arguments,
                            "-o", output, "--verbose"], cwd=ROOT, check=True,
                           capture_output=True, text=True,
                           env=dict(os.environ, PYTHONHASHSEED="0"))
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    generation, seen = 0.0, set()
    for line in child.stdout.splitlines():
        match = _STAGE_LINE.match(line)
        stage = match and match.group(1).split(": ")[-1]  # an atlas prefixes "chart c: "
        if stage in GENERATION_STAGES:
            generation += float(match.group(2))
            seen.add(stage)
    if seen != set(GENERATION_STAGES):
        sys.exit(f"generation_time: `generate -v` printed no time for "
                 f"{sorted(set(GENERATION_STAGES) - seen)}:\n{child.stdout}")
    return generation, cpu, wall


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("models", nargs="*", metavar="MODEL",
                        help="model files or URDFs to measure instead of the built-in models")
    parser.add_argument("--chain", default="",
                        help="comma-separated sizes n of further planar chains")
    parser.add_argument("--repeat", type=int, default=1,
                        help="runs per model; the fastest is shown (default 1)")
    parser.add_argument("--chain-only", action="store_true",
                        help="only the planar chains (built-in and --chain)")
    args = parser.parse_args()
    if args.models:
        jobs = {os.path.splitext(os.path.basename(path))[0]: [path] for path in args.models}
    else:
        jobs = {v.name: v.generate_arguments() for v in variants(benchmarks=True)
                if v.stem == "n_link_chain" or not args.chain_only}
    jobs.update((f"n_link_chain_{n}", ["models/n_link_chain.py", "--set", f"n={n}"])
                for n in args.chain.split(",") if n)
    print(f"{'model':<22} {'derive+CSE+emit s':>17} {'process CPU s':>13} {'wall s':>7} "
          f"{'peak RSS so far MiB':>19}")
    with tempfile.TemporaryDirectory() as output:
        for name, arguments in jobs.items():
            runs = [measure(arguments, output) for _ in range(max(1, args.repeat))]
            generation, cpu, wall = (min(column) for column in zip(*runs))
            peak_kib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss  # max over children
            print(f"{name:<22} {generation:17.2f} {cpu:13.2f} {wall:7.2f} {peak_kib / 1024:19.0f}",
                  flush=True)


if __name__ == "__main__":
    main()
