# SPDX-License-Identifier: BSD-3-Clause
"""What every build the gencoord command runs shares: a lock on its cache folder, logged
steps that show the log's end when they fail, and CMake."""

from __future__ import annotations

import contextlib
import fcntl
import os
import shutil
import subprocess
import sys

from gencoord.tool.errors import ToolError


@contextlib.contextmanager
def locked(directory: str):
    """Holds an exclusive lock on `directory` (created if missing): concurrent builds of the
    same cache entry wait for each other."""
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(directory, ".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)


def run_logged(command: list[str], log_path: str, what: str, verbose: bool) -> None:
    """Runs a build step; on failure shows the end of its log and raises ToolError."""
    if verbose:
        print("  $ " + " ".join(command), file=sys.stderr, flush=True)
    with open(log_path, "a", encoding="utf-8") as log:
        log.write("$ " + " ".join(command) + "\n")
        log.flush()
        result = subprocess.run(command, stdout=None if verbose else log,
                                stderr=subprocess.STDOUT, check=False)
    if result.returncode != 0:
        if not verbose:
            with open(log_path, encoding="utf-8", errors="replace") as log:
                tail = log.read().splitlines()[-40:]
            print("\n".join(tail), file=sys.stderr)
        raise ToolError(f"{what} failed (exit {result.returncode}); the whole log is {log_path}")


def build_targets(build: str, targets: list[str], log_path: str, what: str,
                  verbose: bool) -> None:
    """`cmake --build` of `targets` in `build` with a job per core, logged as run_logged()."""
    jobs = str(max(1, os.cpu_count() or 1))
    run_logged([cmake_program(), "--build", build, "-j", jobs, "--target", *targets], log_path,
               f"compiling {what}", verbose)


def cmake_program() -> str:
    cmake = shutil.which("cmake")
    if not cmake:
        raise ToolError("cmake is not on PATH; install CMake 3.20 or newer "
                        "(Debian: apt-get install cmake)")
    return cmake


def configure_command_start() -> list[str]:
    """`cmake` with the generator and compiler launcher every configuration uses: Ninja where
    it is installed (it starts compiling sooner than make), ccache where it is."""
    command = [cmake_program()]
    if shutil.which("ninja"):
        command += ["-G", "Ninja"]
    ccache = shutil.which("ccache")
    if ccache:
        command.append(f"-DCMAKE_CXX_COMPILER_LAUNCHER={ccache}")
    return command
