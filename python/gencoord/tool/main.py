# SPDX-License-Identifier: BSD-3-Clause
"""gencoord {generate,simulate,crosscheck,python,view,sweep,info}: the command-line entry point."""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import textwrap

from gencoord.generate import cli as generator_cli
from gencoord.generate.failures import report_failure
from gencoord.checks.conservative import conserves_energy
from gencoord.viewer.robot_geometry import package_path
from gencoord.viewer.scene import scene as scene_of

from gencoord import __version__
from gencoord.tool import info, trajectory_svg
from gencoord.tool.cmake_package import cmake_package_dir
from gencoord.tool.driver_build import driver_program, python_module
from gencoord.tool.errors import ToolError
from gencoord.tool.layout import find_layout
from gencoord.tool.model_file import load, refuse_unsupported_kinds, split_settings
from gencoord.tool.python_target import default_python, interpreter_version, write_import_guard
from gencoord.sweep.command import run_sweep
from gencoord.viewer import page as viewer_page

_DESCRIPTION = """\
Generalized-coordinate dynamics from a model file.

  gencoord generate MODEL.py [-o DIR] [--set n=5]     the C++ header (see generate --help)
  gencoord simulate MODEL.py [options]                integrate it: summary, CSV, SVG, HTML
  gencoord view MODEL.py [--csv FILE]                 a trajectory as an HTML page (3D)
  gencoord crosscheck MODEL.py [options]              against the maximal penalty model
  gencoord python MODEL.py [-o DIR]                   its Python module (docs/python.md)
  gencoord info MODEL.py                              what the model file declares
  gencoord sweep SWEEP.toml [--ranks N] [--resume]    an ensemble under MPI (docs/sweep.md)

simulate, crosscheck, python and sweep compile a small program for the model the first time (a CMake
project against the gencoord runtime; a C++17 compiler and CMake are needed) and keep it in a
per-user cache ($GENCOORD_CACHE_DIR, else $XDG_CACHE_HOME/gencoord, else ~/.cache/gencoord)
keyed by the model file's content and options, so the next run starts at once.

A model file is a Python program: gencoord runs it with your rights, as a build runs its
build scripts. Run only model files you trust."""

_TRUST = textwrap.fill(generator_cli.TRUST, 79)

_SIMULATE_EPILOG = """\
Options for the simulation itself go to the compiled program:
  --integrator NAME   rk4 (default), symplectic_euler, backward_euler, ... (see --list)
  --dt DT             step size in s (default 1e-3)
  --duration T        simulated time in s (default 10)
  --q a,b,...  --v a,b,...   initial state (default: the model file's)
  --baumgarte RATE    closed loops, rolling: Baumgarte's feedback at RATE (1/s) keeps the
                      state on the constraints instead of projecting each step
Writes DIR/<name>.csv (t, q, v, energy, positions), DIR/<name>.svg and DIR/<name>.html
(the motion in 3D in any browser; see gencoord view --help)."""

_VIEW_EPILOG = """\
The page holds the trajectory, the model's scene and three.js, and needs nothing else: open
it in any browser. three.js is fetched once from the npm registry into the cache. Controls:
play/pause, time slider, speed, trails, drag to orbit the camera (right-drag pans, wheel
zooms), and a plot of the energy error or a coordinate with the current time marked. A
trajectory of more than 2,000,000 numbers is thinned to that many (every k-th state, the
worst energy error of each k kept)."""

_CROSSCHECK_EPILOG = """\
Options for the cross-check itself go to the compiled program:
  --kappa LO:HI       penalty stiffness range (default 1e2:1e8), --points N per range
  --t T               simulated time (default 5), --samples S compared samples (default 100)
  --integrator rk4|symplectic_euler|backward_euler   the maximal model's integrator
  --max-dt DT, --safety F, --damping C, --reference-dt DT, --min-slope S
  --q a,b,... --v a,b,...   the initial state (default the model file's; --v takes the
                      generalized speeds of a model with free or ball joints)
Writes DIR/<name>_crosscheck.csv and DIR/<name>_crosscheck.svg, and DIR/<name>_crosscheck.html
with DIR/<name>_crosscheck_trajectory.csv: the reduced and the maximal model at the smallest
kappa side by side (see gencoord view --help); exit status 1 when the maximal model does not
converge to the reduced one as kappa grows."""


_SWEEP_EPILOG = """\
The sweep file (TOML) names the model file, the integrator, the end time or an event, the
samples (a grid, Monte Carlo or a Latin hypercube) and what to record; docs/sweep.md and
examples/sweeps/ show its keys. Writes DIR/<stem>.table (the samples) and DIR/<stem>.h5 (the
results: one HDF5 file, written by rank 0). Needs Open MPI and HDF5 (scripts/setup.sh --sweep).
A run that was stopped continues with --resume: the chunks it completed are not run again."""


def _sweep_command(subparsers) -> None:
    parser = subparsers.add_parser(
        "sweep", help="run an ensemble of a model file under MPI",
        description="run an ensemble of a model file under MPI.\n\n" + _TRUST,
        epilog=_SWEEP_EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file", help="the sweep file (TOML)")
    parser.add_argument("--ranks", type=int, default=1,
                        help="MPI ranks (mpirun -np; default 1)")
    parser.add_argument("--threads", type=int, default=0,
                        help="threads per rank (default 0: the node's cores over its ranks)")
    again = parser.add_mutually_exclusive_group()
    again.add_argument("--resume", action="store_true",
                       help="continue the sweep in DIR/<stem>.h5, running only the chunks "
                            "it lacks")
    again.add_argument("--overwrite", action="store_true",
                       help="remove DIR/<stem>.h5 and run the whole sweep again")
    parser.add_argument("--mpi-args", default="", metavar="ARGS",
                        help="more options for mpirun, e.g. \"--hostfile hosts\"")
    parser.add_argument("-o", "--output-dir", default="out",
                        help="where the table and the results go (default: ./out)")
    parser.add_argument("--rebuild", action="store_true",
                        help="generate and compile again even when the cache has the program")
    parser.add_argument("-v", "--verbose", action="store_true",
                        help="show the build's commands and output, the mpirun command, and "
                             "the traceback of an error")


def _model_command(subparsers, name: str, help_text: str, epilog: str):
    # no abbreviations: the program's own options pass through (simulate's --v is not
    # --verbose)
    parser = subparsers.add_parser(name, help=help_text,
                                   description=help_text + ".\n\n" + _TRUST,
                                   epilog=epilog, allow_abbrev=False,
                                   formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("model", help="the model file (any path)")
    parser.add_argument("--set", dest="settings", action="append", default=[],
                        metavar="NAME=VALUE",
                        help="a build option of the model (e.g. n=5) or a parameter value")
    _name_option(parser)
    parser.add_argument("-o", "--output-dir", default="out",
                        help="the output folder (default: ./out)")
    parser.add_argument("--rebuild", action="store_true",
                        help="generate and compile again even when the cache has the program")
    parser.add_argument("-v", "--verbose", action="store_true",
                        help="show the build's commands and output, and the traceback "
                             "of an error")
    return parser


def _name_option(parser) -> None:
    parser.add_argument("--name", help="the model's name instead of the file's stem (a C++ "
                        "identifier; see generate --help)")


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="gencoord", description=_DESCRIPTION,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cmake-dir", action="store_true",
                        help="print a folder for find_package(gencoord) (gencoord_DIR); from a "
                             "checkout or a pip install, builds the runtime first")
    parser.add_argument("--version", action="version", version=f"gencoord {__version__}")
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND")
    subparsers.add_parser("generate", help="the C++ header of a model file", add_help=False)
    simulate_parser = _model_command(subparsers, "simulate", "simulate a model file",
                                     _SIMULATE_EPILOG)
    _model_command(subparsers, "crosscheck",
                   "cross-check a model file against its maximal-coordinate penalty model",
                   _CROSSCHECK_EPILOG)
    python_parser = _model_command(
        subparsers, "python", "build a model file's Python extension module",
        "Copies the module to DIR (default ./out) and prints its path: with DIR on sys.path,\n"
        "`import <name>` gives its Params, metadata, kernels over NumPy arrays, rhs and jac\n"
        "for scipy.integrate.solve_ivp, and simulate(). Needs pybind11 and Python's headers\n"
        "(Debian: pybind11-dev, python3-dev) and NumPy where it is imported.")
    python_parser.add_argument("--python",
                               help="the Python interpreter to build for (default: the first "
                                    "that imports NumPy of the one running gencoord, python3 "
                                    "on PATH and /usr/bin/python3)")
    view_parser = _model_command(subparsers, "view",
                                 "write a trajectory of a model file as an HTML page",
                                 _VIEW_EPILOG)
    view_parser.add_argument("--csv", help="the trajectory (default: DIR/<name>.csv, which "
                                           "gencoord simulate writes)")
    for drawing in (simulate_parser, view_parser):
        drawing.add_argument("--package-path", action="append", default=[], metavar="DIR",
                             help="a folder that holds the packages a URDF's package:// mesh "
                                  "files name (repeatable; ROS_PACKAGE_PATH's are searched "
                                  "after these)")
    _sweep_command(subparsers)
    info_parser = subparsers.add_parser(
        "info", help="what a model file declares",
        description="what a model file declares.\n\n" + _TRUST,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    info_parser.add_argument("model", help="the model file (any path)")
    info_parser.add_argument("--set", dest="settings", action="append", default=[],
                             metavar="NAME=VALUE", help="a build option of the model")
    _name_option(info_parser)
    info_parser.add_argument("-v", "--verbose", action="store_true",
                             help="show the traceback of an error")
    return parser


def _has_option(arguments: list[str], *names: str) -> bool:
    return any(a in names or a.split("=", 1)[0] in names for a in arguments)


def _run(program: str, arguments: list[str]) -> int:
    return subprocess.run([program, *arguments], check=False).returncode


def _prepared(args, forwarded: list[str], driver: str):
    """The loaded model, its `driver` program (built if the cache lacks it), and the
    program's arguments: the forwarded options and the parameters set with --set."""
    loaded = load(args.model, split_settings(args.settings), args.name)
    if driver != "simulate":
        refuse_unsupported_kinds(loaded, driver)
    program = driver_program(find_layout(), loaded.target, driver, rebuild=args.rebuild,
                             verbose=args.verbose)
    arguments = list(forwarded)
    for key, value in loaded.parameters.items():
        arguments += ["--set", f"{key}={value}"]
    return loaded, program, arguments


def _simulate(args, forwarded: list[str]) -> int:
    loaded, program, arguments = _prepared(args, forwarded, "simulate")
    if _has_option(forwarded, "-h", "--help"):
        return _run(program, arguments)
    csv = None
    if not _has_option(forwarded, "--output", "-o"):
        os.makedirs(args.output_dir, exist_ok=True)
        csv = os.path.join(args.output_dir, f"{loaded.target.name}.csv")
        arguments += ["--output", csv]
    status = _run(program, arguments)
    if status == 0 and csv:
        svg = os.path.splitext(csv)[0] + ".svg"
        trajectory_svg.write_svg(csv, svg, loaded.target.name, conserves_energy(loaded.model))
        print(f"picture     {svg}")
        html = os.path.splitext(csv)[0] + ".html"
        _write_view(loaded, csv, html, args.package_path)
        print(f"viewer      {html} (open it in a browser)")
    return status


def _write_view(loaded, csv: str, html: str, packages: list[str]) -> None:
    values = {name: float(value) for name, value in loaded.parameters.items()}
    scene = scene_of(loaded.model, loaded.target.name, values, package_path(packages))
    viewer_page.write_page(csv, scene, html, loaded.target.name)


def _view(args) -> int:
    loaded = load(args.model, split_settings(args.settings), args.name)
    csv = args.csv or os.path.join(args.output_dir, f"{loaded.target.name}.csv")
    if not os.path.isfile(csv):
        raise ToolError(f"{csv}: no such trajectory; run gencoord simulate {args.model} first, "
                        f"or name one with --csv")
    os.makedirs(args.output_dir, exist_ok=True)
    html = os.path.join(args.output_dir,
                        os.path.splitext(os.path.basename(csv))[0] + ".html")
    _write_view(loaded, csv, html, args.package_path)
    print(html)
    return 0


def _crosscheck(args, forwarded: list[str]) -> int:
    loaded, program, arguments = _prepared(args, forwarded, "crosscheck")
    stem = os.path.join(args.output_dir, f"{loaded.target.name}_crosscheck")
    for option, suffix in (("--csv", ".csv"), ("--svg", ".svg"),
                           ("--trajectory", "_trajectory.csv")):
        if not _has_option(forwarded, option, "-h", "--help"):
            os.makedirs(args.output_dir, exist_ok=True)
            arguments += [option, stem + suffix]
    status = _run(program, arguments)
    trajectory = stem + "_trajectory.csv"
    if not _has_option(forwarded, "--trajectory", "-h", "--help") and _has_rows(trajectory):
        _write_view(loaded, trajectory, stem + ".html", [])
        print(f"viewer      {stem}.html: reduced and maximal side by side")
    return status


def _has_rows(csv: str) -> bool:
    """Whether a trajectory CSV holds a row beyond its header."""
    try:
        with open(csv, encoding="utf-8") as handle:
            return len(handle.readlines(1 << 16)) > 1
    except FileNotFoundError:
        return False


def _python(args) -> int:
    loaded = load(args.model, split_settings(args.settings), args.name)
    refuse_unsupported_kinds(loaded, "python")
    python = args.python or default_python()
    built = python_module(find_layout(), loaded.target, python, rebuild=args.rebuild,
                          verbose=args.verbose)
    os.makedirs(args.output_dir, exist_ok=True)
    copy = os.path.join(args.output_dir, os.path.basename(built))
    partial = copy + ".partial"
    shutil.copyfile(built, partial)
    os.replace(partial, copy)  # an importer never sees half a module
    version = interpreter_version(python)
    write_import_guard(copy, loaded.target.name, python, version)
    print(copy)
    print(f"gencoord: built for {python} (Python {version}); import it with that interpreter",
          file=sys.stderr)
    return 0


def _info(args) -> int:
    loaded = load(args.model, split_settings(args.settings), args.name)
    print("\n".join(info.describe(loaded)))
    return 0


def _print_cmake_dir() -> int:
    try:
        print(cmake_package_dir(find_layout()))
    except ToolError as error:
        if not error.shown:
            print(f"{error.prefix}{error}", file=sys.stderr)
        return 1
    return 0


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv and argv[0] == "generate":
        return generator_cli.main(argv[1:], prog="gencoord generate")
    parser = _parser()
    args, forwarded = parser.parse_known_args(argv)
    if args.cmake_dir and args.command is None:
        return _print_cmake_dir()
    if args.command is None:
        parser.print_help()
        return 2
    if forwarded and args.command in ("info", "python", "view", "sweep"):
        parser.error(f"{args.command}: unrecognized arguments: {' '.join(forwarded)}")
    try:
        if args.command == "simulate":
            return _simulate(args, forwarded)
        if args.command == "crosscheck":
            return _crosscheck(args, forwarded)
        if args.command == "python":
            return _python(args)
        if args.command == "view":
            return _view(args)
        if args.command == "sweep":
            return run_sweep(args)
        return _info(args)
    except ToolError as error:
        if not error.shown:
            print(f"{error.prefix}{error}", file=sys.stderr)
        return 1
    except BrokenPipeError:
        # the reader went away (gencoord info MODEL.py | head): stop quietly, and keep the
        # interpreter's final flush of stdout from failing again
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 141
    except (Exception, KeyboardInterrupt) as error:  # one line, never a traceback
        return report_failure(error, getattr(args, "model", None), "gencoord",
                              verbose=args.verbose)
