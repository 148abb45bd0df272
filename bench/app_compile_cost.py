#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""CPU time and peak memory of compiling each translation unit of gencoord's programs.

    python3 bench/app_compile_cost.py [--model models/double_pendulum.py] [--opt -O2]
                                      [--python /usr/bin/python3] [--no-examples]

Configures the repository's example programs (apps/, deformable/apps/) in a build folder
of its own; builds, into a fresh cache, every program the gencoord command compiles for the
model: the simulate and crosscheck drivers, its Python module (for --python, an interpreter
with NumPy) and the sweep driver (skipped, and said so, without MPI and HDF5); then compiles
every one of their source files once more, one at a time, with the optimization level
replaced by --opt, under getrusage: user + system CPU seconds and the compiler's peak
resident memory. One compile at a time, so the figures do not depend on the machine's cores.
"""

from __future__ import annotations

import argparse
import json
import os
import shlex
import subprocess
import sys
import tempfile

REPOSITORY = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
APP_TARGETS = ["atlas_pendulum", "scripted_double_pendulum", "deformable_demo"]

# Run by a child python (PYTHONHASHSEED=0, as every gencoord command runs): builds the
# model's programs into $GENCOORD_CACHE_DIR and prints each build folder ("build: DIR"; the
# generator prints its own lines too).
_BUILD_MODEL_PROGRAMS = """
import os, sys
sys.path.insert(0, os.path.join(sys.argv[1], "python"))
from gencoord.tool.driver_build import driver_program, python_module, sweep_program
from gencoord.tool.errors import ToolError
from gencoord.tool.layout import find_layout
from gencoord.tool.model_file import load
layout, target = find_layout(), load(sys.argv[2], {}).target
for driver in ("simulate", "crosscheck"):
    print("build:", os.path.dirname(driver_program(layout, target, driver)))
print("build:", os.path.dirname(python_module(layout, target, sys.argv[3])))
try:
    print("build:", os.path.dirname(sweep_program(layout, target)))
except ToolError as error:
    print("skipped: the sweep driver:", error, file=sys.stderr)
"""


def compile_commands(build: str) -> list[dict]:
    with open(os.path.join(build, "compile_commands.json"), encoding="utf-8") as handle:
        return json.load(handle)


def measured(command: list[str], directory: str) -> tuple[float, float]:
    """(CPU seconds, peak MiB) of one compile. getrusage's peak of children is the largest
    child so far, so each compile runs under a fresh python of its own that reports it."""
    probe = ("import resource, subprocess, sys; "
             "subprocess.run(sys.argv[1:], check=True); "
             "r = resource.getrusage(resource.RUSAGE_CHILDREN); "
             "print(r.ru_utime + r.ru_stime, r.ru_maxrss / 1024)")
    result = subprocess.run([sys.executable, "-c", probe, *command], cwd=directory,
                            capture_output=True, text=True, check=True)
    cpu, peak = result.stdout.split()
    return float(cpu), float(peak)


def example_entries(build: str) -> list[dict]:
    """The example programs' compile commands, their generated headers built."""
    subprocess.run(["cmake", "-S", REPOSITORY, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                    "-DCMAKE_EXPORT_COMPILE_COMMANDS=ON", "-DGENCOORD_BUILD_TESTS=OFF",
                    "-DGENCOORD_BUILD_BENCHMARKS=OFF", f"-DGENCOORD_PYTHON={sys.executable}"],
                   check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", build, "-j", "2", "--target",
                    "gencoord_model_double_pendulum_header",
                    "gencoord_model_spherical_pendulum_header"],
                   check=True, stdout=subprocess.DEVNULL)
    return [e for e in compile_commands(build)
            if any(f"/{t}.dir/" in e.get("output", e["command"]) for t in APP_TARGETS)]


def with_optimization(command: str, level: str) -> list[str]:
    words = [w for w in shlex.split(command) if not (w.startswith("-O") and len(w) <= 3)]
    return [words[0], level, *words[1:]]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--model", default="models/double_pendulum.py")
    parser.add_argument("--opt", default="-O2")
    parser.add_argument("--python", default="/usr/bin/python3",
                        help="the interpreter the Python module is built for")
    parser.add_argument("--no-examples", action="store_true",
                        help="only the model's programs, not the repository's examples")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="gencoord-compile-cost-") as scratch:
        build = os.path.join(scratch, "build")
        entries = [] if args.no_examples else example_entries(build)
        environment = dict(os.environ, GENCOORD_CACHE_DIR=os.path.join(scratch, "cache"),
                           PYTHONHASHSEED="0")
        built = subprocess.run([sys.executable, "-c", _BUILD_MODEL_PROGRAMS, REPOSITORY,
                                args.model, args.python], check=True, env=environment,
                               capture_output=True, text=True)
        sys.stderr.write(built.stderr)
        # every build folder configures the simulate and crosscheck drivers: each file once
        model_entries: dict[str, dict] = {}
        builds = [line[len("build: "):] for line in built.stdout.splitlines()
                  if line.startswith("build: ")]
        for model_build in builds:
            for e in compile_commands(model_build):
                if "/drivers/" in e["file"] or "/bindings/python/" in e["file"]:
                    model_entries.setdefault(e["file"], e)
        entries += model_entries.values()
        print(f"{'translation unit':<44} {'CPU s':>7} {'peak MiB':>9}"
              f"   ({args.opt}, one at a time)")
        worst_cpu = worst_peak = 0.0
        for entry in entries:
            cpu, peak = measured(with_optimization(entry["command"], args.opt),
                                 entry["directory"])
            worst_cpu, worst_peak = max(worst_cpu, cpu), max(worst_peak, peak)
            name = os.path.relpath(entry["file"], REPOSITORY)
            print(f"{name:<44} {cpu:7.1f} {peak:9.0f}", flush=True)
        print(f"{'largest':<44} {worst_cpu:7.1f} {worst_peak:9.0f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
