# SPDX-License-Identifier: BSD-3-Clause
"""What a sweep will cost, said before anything runs: its samples, steps and results-file
size, and a refusal when the results file would not fit on the disk it goes to (the file is
allocated at its full size when the sweep starts)."""

from __future__ import annotations

import shutil

from gencoord.sweep.spec import Sweep, result_bytes, trajectory_points
from gencoord.tool.errors import ToolError

METADATA = 1 << 20  # HDF5's headers, the attributes and the sweep file, at most


def results_bytes(sweep: Sweep, nq: int, nv: int) -> int:
    """The results file's size: every dataset the program allocates (drivers/sweep/h5_file.hpp)
    at its full size (the samples' values, their results, the trajectory's times, the chunk
    flags), plus a bound on the metadata; q has nq entries, v nv."""
    chunks = -(-sweep.count // sweep.chunk)
    return (sweep.count * (8 * len(sweep.variables) + result_bytes(sweep, nq, nv))
            + 8 * trajectory_points(sweep) + chunks + METADATA)


def size_text(size: float) -> str:
    for unit in ("bytes", "kB", "MB", "GB", "TB"):
        if size < 1000 or unit == "TB":
            return f"{size:.0f} {unit}" if unit == "bytes" else f"{size:.3g} {unit}"
        size /= 1000
    raise AssertionError("unreachable")


def summary(sweep: Sweep, nq: int, nv: int) -> str:
    """The line `gencoord sweep` prints before it runs."""
    return (f"gencoord: {sweep.name}: {sweep.count} samples x {sweep.steps} steps "
            f"({sweep.count * sweep.steps:,} steps in all), results file about "
            f"{size_text(results_bytes(sweep, nq, nv))}")


def check_disk(sweep: Sweep, nq: int, nv: int, folder: str, replaced: int = 0) -> None:
    """\\raises ToolError if the results file would not fit in the free space of `folder`'s
    disk (plus `replaced` bytes: an old results file that --overwrite removes)."""
    needed = results_bytes(sweep, nq, nv)
    free = shutil.disk_usage(folder).free + replaced
    if needed > free:
        raise ToolError(f"the results file of {sweep.name} would take about {size_text(needed)}, "
                        f"but the disk of {folder} has {size_text(free)} free; free some space, "
                        "record less (fewer samples, a larger trajectory_every, no trajectory) "
                        "or give another --output-dir")
