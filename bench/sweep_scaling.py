#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Strong scaling of gencoord sweep on this machine, and the cost of a chunk.

    python3 bench/sweep_scaling.py [--points 128] [--ranks 1,2,4] [--repeat 3]
                                   [-o out/sweep_scaling]

1. The time-to-flip sweep of examples/sweeps/double_pendulum_flip.toml on a coarser grid
   (--points per angle; chunks of one grid row) with 1 rank and 1 thread, 1 rank and 2
   threads, and each of --ranks with 1 thread: the sweep's wall time (the program's own
   "this run" figure: from the first chunk handed out to the last written), the speed-up over
   1 x 1, and the cost per sample and per RK4 step of one thread (steps counted from the
   results: a sample runs to its flip, or to the cap). Each layout runs --repeat times, in
   turn with the others; the table gives the minimum (other work on the machine only slows a
   run down) and the median over the rounds.
2. The cost of a chunk: 4096 samples of one step each, in chunks of 1 and in one chunk, on 1
   and 2 ranks, in turn; the difference over 4095 chunks is what one chunk costs beyond its samples
   (hand-out, the results' trip to rank 0, their rows written; rank 0 writes every result
   that has arrived at once, with one pair of syncs to disk).
Needs what gencoord sweep needs (scripts/setup.sh --sweep); h5py for /usr/bin/python3."""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import time

REPOSITORY = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(REPOSITORY, "examples", "sweeps", "double_pendulum_flip.toml")
STEPS = """\
import h5py, numpy, sys
with h5py.File(sys.argv[1], "r") as f:
    flip = f["event_time"][()]
    dt, cap = float(f.attrs["dt"]), int(f.attrs["steps"])
steps = numpy.where(numpy.isnan(flip), cap, numpy.round(flip / dt))
print(int(steps.sum()))
"""


def sweep_file(folder: str, name: str, points: int, chunk: int, t_end: str) -> str:
    with open(EXAMPLE, encoding="utf-8") as handle:
        text = handle.read()
    text = text.replace('file = "../../models/', f'file = "{REPOSITORY}/models/')
    text = text.replace("points = 512", f"points = {points}")
    text = text.replace("chunk = 512 ", f"chunk = {chunk} ")
    text = text.replace("t_end = 100.0", f"t_end = {t_end}")
    path = os.path.join(folder, f"{name}.toml")
    with open(path, "w", encoding="utf-8") as handle:
        handle.write(text)
    return path


def run(path: str, output: str, ranks: int, threads: int) -> tuple[float, float, str]:
    """The sweep's own wall time, the whole command's (mpirun's start, reading the table,
    creating the file included), in seconds, and the summary's line on rank 0's writes."""
    command = [sys.executable, os.path.join(REPOSITORY, "gencoord"), "sweep", path,
               "--ranks", str(ranks), "--threads", str(threads), "-o", output, "--overwrite"]
    start = time.monotonic()
    result = subprocess.run(command, capture_output=True, text=True, check=False)
    whole = time.monotonic() - start
    if result.returncode != 0:
        sys.exit(result.stdout + result.stderr)
    writes = re.search(r"writes +(.*)", result.stdout).group(1)
    return float(re.search(r"samples in ([0-9.]+) s", result.stdout).group(1)), whole, writes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--points", type=int, default=128)
    parser.add_argument("--ranks", default="1,2,4")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("-o", "--output-dir", default="out/sweep_scaling")
    args = parser.parse_args()
    os.makedirs(args.output_dir, exist_ok=True)
    points = args.points
    flip = sweep_file(args.output_dir, f"flip_{points}", points, points, "100.0")
    layouts = [(1, 1), (1, 2)] + [(int(r), 1) for r in args.ranks.split(",") if r != "1"]
    print(f"1. time to flip, {points} x {points} = {points * points} samples, chunks of "
          f"{points}, on {os.cpu_count()} cores; {args.repeat} rounds\n")
    print("| ranks x threads | sweep min (s) | median (s) | speed-up (min) | speed-up (median) "
          "| samples/s (min) | command min (s) | rank 0's writes |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    rounds = {layout: [] for layout in layouts}
    for _ in range(args.repeat):
        for layout in layouts:
            rounds[layout].append(run(flip, args.output_dir, *layout))
    base_min, base_median = seconds_of(rounds[(1, 1)])
    for (ranks, threads), measured in rounds.items():
        fastest, median = seconds_of(measured)
        whole = min(m[1] for m in measured)
        print(f"| {ranks} x {threads} | {fastest:.2f} | {median:.2f} | {base_min / fastest:.2f} "
              f"| {base_median / median:.2f} | {points * points / fastest:.0f} | {whole:.2f} "
              f"| {min(measured)[2]} |", flush=True)
    results = os.path.join(args.output_dir, f"flip_{points}.h5")
    steps = int(subprocess.run(["/usr/bin/python3", "-c", STEPS, results], capture_output=True,
                               text=True, check=True).stdout)
    print(f"\none thread (1 x 1, min): {base_min / points ** 2 * 1e3:.3f} ms per sample, "
          f"{steps} RK4 steps in all, {base_min / steps * 1e9:.0f} ns per step "
          "(energy and event included)\n")

    one_step = sweep_file(args.output_dir, "one_step", 64, 1, "0.01")
    whole = sweep_file(args.output_dir, "one_step_whole", 64, 4096, "0.01")
    print(f"2. 4096 samples of one step each; {args.repeat} rounds, the layouts in turn\n")
    print("| ranks | 4096 chunks of 1, min (s) | median (s) | 1 chunk of 4096, min (s) "
          "| median (s) | per chunk, min (ms) | per chunk, median (ms) |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    chunked = {ranks: ([], []) for ranks in (1, 2)}
    for _ in range(args.repeat):
        for ranks, (many, single) in chunked.items():
            many.append(run(one_step, args.output_dir, ranks, 1))
            single.append(run(whole, args.output_dir, ranks, 1))
    for ranks, (many, single) in chunked.items():
        (many_min, many_median), (single_min, single_median) = map(seconds_of, (many, single))
        print(f"| {ranks} | {many_min:.3f} | {many_median:.3f} | {single_min:.3f} "
              f"| {single_median:.3f} | {(many_min - single_min) / 4095 * 1e3:.3f} "
              f"| {(many_median - single_median) / 4095 * 1e3:.3f} |", flush=True)


def seconds_of(measured: list[tuple[float, float, str]]) -> tuple[float, float]:
    """The minimum and the median of the sweeps' own times."""
    seconds = [m[0] for m in measured]
    return min(seconds), statistics.median(seconds)


if __name__ == "__main__":
    main()
