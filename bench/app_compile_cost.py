#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""CPU time and peak memory of compiling each translation unit of gencoord's programs.

    python3 bench/app_compile_cost.py [--model models/double_pendulum.py] [--opt -O2]

Configures the repository's example programs (apps/, deformable/apps/) in a build folder
of its own, builds the model's drivers through `gencoord simulate` into a fresh cache, and
compiles every one of their source files once more, one at a time, with the optimization
level replaced by --opt, under getrusage: user + system CPU seconds and the compiler's peak
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


def with_optimization(command: str, level: str) -> list[str]:
    words = [w for w in shlex.split(command) if not (w.startswith("-O") and len(w) <= 3)]
    return [words[0], level, *words[1:]]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--model", default="models/double_pendulum.py")
    parser.add_argument("--opt", default="-O2")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="gencoord-compile-cost-") as scratch:
        build = os.path.join(scratch, "build")
        subprocess.run(["cmake", "-S", REPOSITORY, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                        "-DCMAKE_EXPORT_COMPILE_COMMANDS=ON", "-DGENCOORD_BUILD_TESTS=OFF",
                        "-DGENCOORD_BUILD_BENCHMARKS=OFF", f"-DGENCOORD_PYTHON={sys.executable}"],
                       check=True, stdout=subprocess.DEVNULL)
        # the generated headers the examples include
        subprocess.run(["cmake", "--build", build, "-j", "2", "--target",
                        "gencoord_model_double_pendulum_header",
                        "gencoord_model_spherical_pendulum_header"],
                       check=True, stdout=subprocess.DEVNULL)
        environment = dict(os.environ, GENCOORD_CACHE_DIR=os.path.join(scratch, "cache"))
        subprocess.run([sys.executable, os.path.join(REPOSITORY, "gencoord"), "simulate",
                        args.model, "--duration", "0", "-o", os.path.join(scratch, "out")],
                       check=True, env=environment, stdout=subprocess.DEVNULL)
        entries = [e for e in compile_commands(build)
                   if any(f"/{t}.dir/" in e.get("output", e["command"]) for t in APP_TARGETS)]
        cache = os.path.join(scratch, "cache")
        # the model's entry; the runtime's (runtime-<key>) is built once per user
        model_entry = next(e for e in sorted(os.listdir(cache)) if not e.startswith("runtime-"))
        driver_build = os.path.join(cache, model_entry, "build")
        entries += [e for e in compile_commands(driver_build)
                    if "/drivers/" in e["file"]]
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
