# SPDX-License-Identifier: BSD-3-Clause
"""The compiled runtime (gencoord::runtime) built once per user into the cache, for the
programs the gencoord command builds from a source checkout.

Every model's drivers, Python modules and sweep program link the same runtime library, so it
is built once, by the checkout's own CMake project with everything but the runtime switched
off, and installed (the install component `runtime`: headers, library, exported targets) into
`runtime-<key>/prefix` of the cache. The key is the hash of what decides the library: the
runtime's sources and CMake files, the compiler, CXXFLAGS and the build type. An installation
of gencoord (cmake --install) has its runtime already and needs none of this.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import sys

from gencoord.tool.build_steps import (build_targets, cmake_program, configure_command_start,
                                       locked, run_logged)
from gencoord.tool.layout import Layout, cache_dir, compiler

BUILD_TYPE = "Release"

# what the runtime's build reads, relative to the checkout
_RUNTIME_SOURCES = ("runtime/include", "runtime/src", "runtime/CMakeLists.txt",
                    "cmake/install.cmake", "cmake/gencoordConfig.cmake.in", "CMakeLists.txt")

# the checkout's project with every part but the runtime switched off
_ONLY_THE_RUNTIME = [f"-DCMAKE_BUILD_TYPE={BUILD_TYPE}", "-DGENCOORD_BUILD_TESTS=OFF",
                     "-DGENCOORD_BUILD_BENCHMARKS=OFF", "-DGENCOORD_BUILD_APPS=OFF",
                     "-DGENCOORD_BUILD_MODELS=OFF", "-DGENCOORD_BUILD_DEFORMABLE=OFF",
                     "-DGENCOORD_BUILD_PYTHON=OFF", "-DGENCOORD_INSTALL=ON"]


def _files(path: str):
    if os.path.isfile(path):
        yield path
        return
    for folder, subfolders, files in os.walk(path):
        subfolders.sort()
        for file_name in sorted(files):
            yield os.path.join(folder, file_name)


def runtime_key(source_dir: str) -> str:
    digest = hashlib.sha256()
    for relative in _RUNTIME_SOURCES:
        for path in _files(os.path.join(source_dir, relative)):
            digest.update(os.path.relpath(path, source_dir).encode() + b"\0")
            with open(path, "rb") as handle:
                digest.update(handle.read())
    for part in (compiler(), os.environ.get("CXXFLAGS", ""), BUILD_TYPE):
        digest.update(b"\0" + part.encode())
    return digest.hexdigest()[:16]


def runtime_targets_dir(layout: Layout, *, verbose: bool = False) -> str | None:
    """The folder of the cached runtime's gencoordTargets.cmake, built and installed the first
    time; None for an installation of gencoord, whose find_package(gencoord) has the runtime."""
    if not layout.source_dir:
        return None
    entry = os.path.join(cache_dir(), f"runtime-{runtime_key(layout.source_dir)}")
    prefix = os.path.join(entry, "prefix")
    targets_dir = os.path.join(prefix, "lib", "cmake", "gencoord")
    stamp = os.path.join(entry, "installed")
    with locked(entry):
        if os.path.isfile(stamp):
            return targets_dir
        print(f"gencoord: building the runtime library (once per user and version; cached in "
              f"{entry})", file=sys.stderr, flush=True)
        build = os.path.join(entry, "build")
        shutil.rmtree(prefix, ignore_errors=True)
        log = os.path.join(entry, "build.log")
        run_logged([*configure_command_start(), "-S", layout.source_dir, "-B", build,
                    f"-DCMAKE_INSTALL_PREFIX={prefix}", *_ONLY_THE_RUNTIME], log,
                   "configuring the runtime library", verbose)
        build_targets(build, ["gencoord_runtime"], log, "the runtime library", verbose)
        run_logged([cmake_program(), "--install", build, "--component", "runtime"], log,
                   "installing the runtime library into the cache", verbose)
        with open(stamp, "w", encoding="utf-8") as handle:
            handle.write(prefix + "\n")
    return targets_dir
