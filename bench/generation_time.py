#!/usr/bin/env python3
"""Generation time (load, check, derive, CSE, emit) of every built-in model, and peak memory.

    PYTHONHASHSEED=0 python3 bench/generation_time.py [--chain 1,2,5,10,20]

Each model is generated in a fresh process (as the build does), into a temporary folder.
"""
import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = ["pendulum", "pendulum_3d", "spherical_pendulum", "double_pendulum",
          "bead_on_rotating_hoop", "cart_pole", "spring_pendulum", "kapitza_pendulum",
          "falling_cat", "rigid_body_euler", "stiff_chain"]


def measure(arguments, output):
    start = time.perf_counter()
    child = subprocess.run([sys.executable, os.path.join(ROOT, "generate"), *arguments,
                            "-o", output, "--quiet"], cwd=ROOT, check=True,
                           env=dict(os.environ, PYTHONHASHSEED="0"))
    del child
    seconds = time.perf_counter() - start
    peak_kib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss  # max over children
    return seconds, peak_kib


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chain", default="1,2,5,10,20",
                        help="comma-separated chain sizes n (default 1,2,5,10,20)")
    args = parser.parse_args()
    jobs = [(m, [f"models/{m}.py"]) for m in MODELS]
    jobs += [(f"n_link_chain_{n}", ["models/n_link_chain.py", "--set", f"n={n}"])
             for n in args.chain.split(",")]
    print(f"{'model':<24} {'generation (s)':>14} {'peak RSS so far (MiB)':>22}")
    with tempfile.TemporaryDirectory() as output:
        for name, arguments in jobs:
            seconds, peak = measure(arguments, output)
            print(f"{name:<24} {seconds:14.2f} {peak / 1024:22.0f}", flush=True)


if __name__ == "__main__":
    main()
