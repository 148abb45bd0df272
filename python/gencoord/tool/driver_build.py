# SPDX-License-Identifier: BSD-3-Clause
"""Builds the drivers (drivers/*.cpp) or the Python module of one model file into the
per-user cache, once.

A cache entry is a folder named after the model and a key: the hash of the model file, its
options, gencoord's own sources (generator, templates, drivers, bindings, runtime), the Python
and SymPy that generate, and the C++ compiler. It holds the generated header (and, once
`crosscheck` asks for it, the header generated with --maximal, which adds the maximal model
that only that driver runs), a small CMake project that compiles the drivers and the module
against the runtime (the one the cache holds for every model, runtime_build.py, or an
installation's), its builds (the drivers', and one per Python interpreter for the module),
and in each build a stamp written only after everything it builds is complete: without it the
build runs again. A lock file serializes concurrent builds of the same entry. Files the model
file imports are not part of the key; `--rebuild` forces a fresh build.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import shutil
import subprocess
import sys
from dataclasses import dataclass

import sympy

from gencoord.generate import cli as generator_cli

from gencoord.tool.build_steps import build_targets, configure_command_start, locked, run_logged
from gencoord.tool.errors import ToolError
from gencoord.tool.layout import Layout, cache_dir, compiler
from gencoord.tool.runtime_build import runtime_targets_dir

_SOURCE_SUFFIXES = (".py", ".j2", ".hpp", ".cpp", ".cmake", ".txt")

_PROJECT = """\
# Drivers for one gencoord model, written by the gencoord command; safe to delete.
cmake_minimum_required(VERSION 3.20)
project(gencoord_drivers_{name} LANGUAGES CXX)
if(GENCOORD_RUNTIME_DIR)  # a checkout: its runtime, built once per user into the cache
  find_package(Eigen3 3.4 REQUIRED NO_MODULE)
  set(THREADS_PREFER_PTHREAD_FLAG ON)
  find_package(Threads REQUIRED)
  include("${{GENCOORD_RUNTIME_DIR}}/gencoordTargets.cmake")
  include("${{GENCOORD_SOURCE_DIR}}/cmake/gencoord.cmake")
else()  # an installation
  find_package(gencoord REQUIRED)
endif()
include("${{GENCOORD_DRIVERS_DIR}}/gencoord_drivers.cmake")
add_library(model INTERFACE)
target_include_directories(model INTERFACE "${{CMAKE_CURRENT_SOURCE_DIR}}/../include")
set_target_properties(model PROPERTIES GENCOORD_MODEL_NAME {name}
                      GENCOORD_MODEL_CLASS gencoord::models::{class_name})
add_library(model_maximal INTERFACE)  # the same model with its maximal model (--maximal)
target_include_directories(model_maximal INTERFACE
                           "${{CMAKE_CURRENT_SOURCE_DIR}}/../include-maximal")
gencoord_add_driver(simulate DRIVER simulate MODEL model
                    CLASS gencoord::models::{class_name} HEADER generated/{name}.hpp)
gencoord_add_driver(crosscheck DRIVER crosscheck MODEL model_maximal
                    CLASS gencoord::models::{class_name} HEADER generated/{name}.hpp)
if(GENCOORD_PYTHON_MODULE)
  gencoord_add_python_module(python_module MODEL_TARGET model)
endif()
if(GENCOORD_SWEEP_DRIVER)  # only this program needs MPI and HDF5 (FindHDF5 compiles C)
  enable_language(C)
  set(MPI_CXX_SKIP_MPICXX ON)
  find_package(MPI REQUIRED COMPONENTS CXX)
  find_package(HDF5 REQUIRED COMPONENTS C)
  gencoord_add_driver(sweep DRIVER sweep MODEL model
                      CLASS gencoord::models::{class_name} HEADER generated/{name}.hpp)
endif()
"""


@dataclass(frozen=True)
class ModelTarget:
    """A model file with its build options, and the names the generator gives it."""
    path: str
    options: dict[str, str]
    name: str          # e.g. n_link_chain_5: the header's stem
    class_name: str    # e.g. NLinkChain5: gencoord::models::<class_name>
    stem: str | None = None  # generate --name: replaces the file's stem in `name`


def _fingerprint(layout: Layout) -> str:
    digest = hashlib.sha256()
    for directory in layout.fingerprint_dirs:
        for folder, subfolders, files in os.walk(directory):
            subfolders[:] = sorted(d for d in subfolders if d != "__pycache__")
            for file_name in sorted(files):
                if not file_name.endswith(_SOURCE_SUFFIXES):
                    continue
                path = os.path.join(folder, file_name)
                digest.update(os.path.relpath(path, layout.root).encode())
                with open(path, "rb") as handle:
                    digest.update(handle.read())
    return digest.hexdigest()


DRIVER_FLAGS = "-O2 -DNDEBUG"


def entry_dir(layout: Layout, target: ModelTarget) -> str:
    digest = hashlib.sha256()
    with open(target.path, "rb") as handle:
        digest.update(handle.read())
    for part in (json.dumps(target.options, sort_keys=True), _fingerprint(layout),
                 sys.version, sympy.__version__, compiler(), os.environ.get("CXXFLAGS", ""),
                 DRIVER_FLAGS):
        digest.update(b"\0" + part.encode())
    return os.path.join(cache_dir(), f"{target.name}-{digest.hexdigest()[:16]}")


def _generate_header(target: ModelTarget, include_dir: str, maximal: bool) -> None:
    arguments = [target.path, "-o", os.path.join(include_dir, "generated")]
    if maximal:
        arguments.append("--maximal")
    for key, value in target.options.items():
        arguments += ["--set", f"{key}={value}"]
    if target.stem:
        arguments += ["--name", target.stem]
    if generator_cli.main(arguments) != 0:
        raise ToolError(f"{target.path}: generation failed (the error is above)", shown=True)


def _configure_command(layout: Layout, project: str, build: str, verbose: bool) -> list[str]:
    command = [*configure_command_start(), "-S", project, "-B", build,
               # -O2, not CMake's -O3: a small model's Python module compiles in 26 s of CPU
               # instead of 30 (g++ 12)
               "-DCMAKE_BUILD_TYPE=Release", f"-DCMAKE_CXX_FLAGS_RELEASE={DRIVER_FLAGS}",
               "-DCMAKE_EXPORT_COMPILE_COMMANDS=ON",
               f"-DGENCOORD_PYTHON={sys.executable}",
               f"-DGENCOORD_DRIVERS_DIR={layout.drivers_dir}"]
    runtime = runtime_targets_dir(layout, verbose=verbose)
    if runtime:
        command += [f"-DGENCOORD_SOURCE_DIR={layout.source_dir}",
                    f"-DGENCOORD_RUNTIME_DIR={runtime}"]
    else:
        command.append(f"-DCMAKE_PREFIX_PATH={layout.prefix}")
    return command


def _stamp(build: str, cmake_targets: list[str]) -> str:
    return os.path.join(build, "-".join(cmake_targets) + ".built")


def _forget_builds(entry: str) -> None:
    """Removes every build's stamp in a cache entry: each rebuilds against the header."""
    for folder in os.listdir(entry):
        if folder.startswith("build"):
            for name in os.listdir(os.path.join(entry, folder)):
                if name.endswith(".built"):
                    os.unlink(os.path.join(entry, folder, name))


def _cached_build(layout: Layout, target: ModelTarget, build: str, outputs: list[str], *,
                  cmake_targets: list[str], configure: list[str], what: str, rebuild: bool,
                  verbose: bool, needs: str = "", maximal: bool = False) -> None:
    """Builds `cmake_targets` of the model's project in `build` unless a stamp there says that
    `outputs` were built completely; the cache entry is locked meanwhile. `rebuild`
    regenerates the header, so every build of the entry is done again when next asked for.
    `needs` says what the configuration needs beyond a compiler and CMake, when it fails;
    `maximal`, that the targets read the header generated with --maximal."""
    entry = entry_dir(layout, target)
    stamp = _stamp(build, cmake_targets)
    with locked(entry):
        if rebuild:
            _forget_builds(entry)
        if os.path.isfile(stamp) and all(map(os.path.isfile, outputs)):
            return
        print(f"gencoord: building {what} (once; cached in {entry})", file=sys.stderr,
              flush=True)
        for output in outputs:
            with contextlib.suppress(FileNotFoundError):
                os.unlink(output)  # a link cut short would look up to date
        project = _write_project(target, entry, rebuild, maximal)
        log = os.path.join(entry, "build.log")
        if not os.path.isfile(os.path.join(build, "CMakeCache.txt")):
            run_logged(_configure_command(layout, project, build, verbose) + configure, log,
                       f"configuring the project of {what}{needs}", verbose)
        build_targets(build, cmake_targets, log, what, verbose)
        with open(stamp, "w", encoding="utf-8") as handle:
            handle.write("\n".join(outputs) + "\n")


def driver_program(layout: Layout, target: ModelTarget, driver: str, *, rebuild: bool = False,
                   verbose: bool = False) -> str:
    """The path of `driver` built for `target`, compiled the first time it is asked for: a
    model's first `simulate` waits for that program alone."""
    build = os.path.join(entry_dir(layout, target), "build")
    program = os.path.join(build, driver)
    _cached_build(layout, target, build, [program], cmake_targets=[driver], configure=[],
                  what=f"the {driver} program for {target.name}", rebuild=rebuild,
                  verbose=verbose, maximal=driver == "crosscheck")
    return program


def sweep_program(layout: Layout, target: ModelTarget, *, rebuild: bool = False,
                  verbose: bool = False) -> str:
    """The path of the sweep driver built for `target`, in a build of its own: only it needs
    MPI and HDF5, so the other drivers build without them."""
    build = os.path.join(entry_dir(layout, target), "build-sweep")
    program = os.path.join(build, "sweep")
    _cached_build(layout, target, build, [program], cmake_targets=["sweep"],
                  configure=["-DGENCOORD_SWEEP_DRIVER=ON"],
                  what=f"the sweep program for {target.name}",
                  needs=" (it needs MPI and HDF5: scripts/setup.sh --sweep installs Debian's "
                        "libopenmpi-dev and libhdf5-dev)", rebuild=rebuild, verbose=verbose)
    return program


def generated_header(layout: Layout, target: ModelTarget) -> str:
    """The header generated for `target` in its cache entry (after a build)."""
    return os.path.join(entry_dir(layout, target), "include", "generated", f"{target.name}.hpp")


def _write_project(target: ModelTarget, entry: str, rebuild: bool, maximal: bool) -> str:
    """Generates the header unless the entry has it (and the one with the maximal model if
    `maximal`), writes the CMake project, returns its folder. `rebuild` regenerates the
    header and drops the maximal one, which its next user generates again."""
    include_dir = os.path.join(entry, "include")
    maximal_dir = os.path.join(entry, "include-maximal")
    if rebuild:
        shutil.rmtree(maximal_dir, ignore_errors=True)
    header = os.path.join("generated", f"{target.name}.hpp")
    if rebuild or not os.path.isfile(os.path.join(include_dir, header)):
        _generate_header(target, include_dir, maximal=False)
    if maximal and not os.path.isfile(os.path.join(maximal_dir, header)):
        _generate_header(target, maximal_dir, maximal=True)
    project = os.path.join(entry, "project")
    os.makedirs(project, exist_ok=True)
    with open(os.path.join(project, "CMakeLists.txt"), "w", encoding="utf-8") as handle:
        handle.write(_PROJECT.format(name=target.name, class_name=target.class_name))
    return project


_PROBE = ("import sys, sysconfig; print('gencoord-python'); print(sys.version.splitlines()[0]); "
          "print(sysconfig.get_config_var('EXT_SUFFIX'))")


def _interpreter(python: str) -> tuple[str, str]:
    """The version and the extension-module suffix of the Python `python`; a ToolError if it
    cannot be run or does not answer as a Python 3 does."""
    refused = f"{python} is not a Python interpreter that runs here"
    try:
        answer = subprocess.run([python, "-c", _PROBE], capture_output=True, text=True,
                                check=False, stdin=subprocess.DEVNULL, timeout=60)
    except (OSError, subprocess.TimeoutExpired) as error:
        reason = error.strerror if isinstance(error, OSError) else "it did not answer in 60 s"
        raise ToolError(f"{refused} ({reason}); name one with --python") from None
    lines = answer.stdout.splitlines()
    if answer.returncode != 0 or len(lines) != 3 or lines[0] != "gencoord-python" \
            or lines[2] in ("", "None"):
        raise ToolError(f"{refused} (it did not answer as Python 3 does); name one with "
                        "--python")
    return lines[1], lines[2]


def python_module(layout: Layout, target: ModelTarget, python: str, *, rebuild: bool = False,
                  verbose: bool = False) -> str:
    """The path of the model's Python extension module built for `python` (an interpreter),
    built into the cache entry the first time; one build folder per interpreter."""
    version, suffix = _interpreter(python)
    key = hashlib.sha256((os.path.realpath(python) + "\0" + version).encode()).hexdigest()[:12]
    build = os.path.join(entry_dir(layout, target), f"build-python-{key}")
    module = os.path.join(build, target.name + suffix)
    _cached_build(layout, target, build, [module], cmake_targets=["python_module"],
                  configure=["-DGENCOORD_PYTHON_MODULE=ON", f"-DPYTHON_EXECUTABLE={python}"],
                  what=f"the Python module of {target.name} for {python}",
                  needs=" (it needs pybind11 and Python's headers: Debian's pybind11-dev and "
                        "python3-dev)", rebuild=rebuild, verbose=verbose)
    return module
