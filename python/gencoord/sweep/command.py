# SPDX-License-Identifier: BSD-3-Clause
"""`gencoord sweep FILE`: checks the sweep file, builds the model's sweep program, writes the
sample table and runs the program under mpirun; the program prints the progress line and the
summary, and writes the results file."""

from __future__ import annotations

import os
import shlex
import shutil
import subprocess

from gencoord.tool.driver_build import entry_dir, generated_header, sweep_program
from gencoord.tool.errors import ToolError
from gencoord.tool.layout import find_layout
from gencoord.tool.model_file import load
from gencoord.sweep import preflight, spec
from gencoord.sweep.source import read_source
from gencoord.sweep.table import table_text, write_table

MAX_SWEEP_TEXT = 32 * 1024  # the file is kept as an HDF5 attribute, which must stay small


def _banner(header: str) -> str:
    """The generated header's leading comment: model, generator and SymPy versions."""
    lines = []
    with open(header, encoding="utf-8") as handle:
        for line in handle:
            if not line.startswith("//"):
                break
            lines.append(line.rstrip("\n"))
    return "\n".join(lines)


def _load_model(sweep: spec.Sweep):
    try:
        loaded = load(sweep.model_file, dict(sweep.options))
    except ToolError as error:
        raise sweep.source.error(("model", "options"), str(error)) from None
    if loaded.parameters:
        names = ", ".join(loaded.parameters)
        raise sweep.source.error(("model", "options"),
                                 f"{names}: a parameter of the model, not a build option; "
                                 "give it in [model] parameters")
    return loaded


def mpirun_command(ranks: int, extra: list[str]) -> list[str]:
    """mpirun for `ranks` ranks (Open MPI's options): on this machine, or where `extra`
    (--mpi-args: a hostfile, a mapping) says."""
    mpirun = shutil.which("mpirun")
    if not mpirun:
        raise ToolError("mpirun is not on PATH; scripts/setup.sh --sweep installs Open MPI "
                        "(Debian's openmpi-bin)")
    command = [mpirun, "-np", str(ranks)]
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        command.append("--allow-run-as-root")  # Open MPI refuses root without it
    if not extra:
        # on this machine: Open MPI counts cores, not hardware threads, as slots and refuses
        # more ranks than slots; more ranks than cores are slower, not wrong
        command.append("--oversubscribe")
    # each rank runs several threads; Open MPI would bind each rank to one core
    command += ["--bind-to", "none", *extra]
    return command


def run_sweep(args) -> int:
    if args.ranks < 1 or args.threads < 0:
        raise ToolError("--ranks needs at least 1, --threads at least 0 (0: the cores shared "
                        "among the ranks)")
    source = read_source(args.file)
    if len(source.text.encode()) > MAX_SWEEP_TEXT:
        raise ToolError(f"{args.file}: the sweep file is larger than {MAX_SWEEP_TEXT} bytes; "
                        "it is kept in the results file, so keep it to settings and samples")
    sweep = spec.parse(source)
    loaded = _load_model(sweep)
    model = loaded.model
    coordinates = [c.name for c in model.coordinates]
    speeds = [s.name for s in model.speeds] if model.has_generalized_speeds else None
    sweep = spec.check_names(sweep, coordinates, [p.name for p in model.parameters], speeds)
    os.makedirs(args.output_dir, exist_ok=True)
    stem = os.path.join(os.path.abspath(args.output_dir), sweep.name)
    table, results = stem + ".table", stem + ".h5"
    if os.path.exists(results) and not (args.resume or args.overwrite):
        raise ToolError(f"{results} exists: --resume continues that sweep, --overwrite starts "
                        "it again")
    nq, nv = model.nq, model.nv
    print(preflight.summary(sweep, nq, nv), flush=True)
    if not (args.resume and os.path.exists(results)):  # a resumed file is already allocated
        old = os.path.getsize(results) if os.path.exists(results) else 0
        preflight.check_disk(sweep, nq, nv, args.output_dir, replaced=old)
    layout = find_layout()
    program = sweep_program(layout, loaded.target, rebuild=args.rebuild, verbose=args.verbose)
    header = generated_header(layout, loaded.target)
    if args.overwrite and os.path.exists(results):
        os.unlink(results)
    build = os.path.basename(entry_dir(layout, loaded.target))  # the program's cache key
    write_table(table, table_text(sweep, loaded.target.name, build, _banner(header)))
    if args.resume and not os.path.exists(results):
        print(f"gencoord: {results} does not exist yet; nothing to resume, starting the sweep")
    elif args.resume:
        # the program says, without MPI, whether the file holds this sweep and how much
        check = [program, "--check", "--table", table, "--output", results]
        if subprocess.run(check, check=False).returncode != 0:
            raise ToolError("", shown=True)  # the program said why
    command = mpirun_command(args.ranks, shlex.split(args.mpi_args)) + [
        program, "--table", table, "--output", results, "--threads", str(args.threads)]
    if args.resume:
        command.append("--resume")
    if args.verbose:
        print("  $ " + " ".join(command), flush=True)
    status = subprocess.run(command, check=False).returncode
    if status != 0 and not os.path.exists(results):
        raise ToolError(f"the sweep stopped before it wrote {os.path.relpath(results)} "
                        f"(mpirun exit status {status}; the error is above)")
    if status != 0:
        raise ToolError(f"the sweep stopped (mpirun exit status {status}; a rank that died is "
                        f"named above); the chunks it completed are kept in "
                        f"{os.path.relpath(results)}, and gencoord sweep {args.file} --resume "
                        "runs the rest")
    return 0
