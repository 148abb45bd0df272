# SPDX-License-Identifier: BSD-3-Clause
"""The sample table: what the sweep program reads (drivers/sweep/table.hpp). A text file of
`key value` lines, then `samples N` and N rows of values, every number written so that it
reads back to the same double (repr). Its `digest` line is the SHA-256 of everything after
that line: the results file keeps it, so that --resume continues only the same sweep, run by
the same build of the model's program."""

from __future__ import annotations

import hashlib
import os

from gencoord.sweep.samples import rows
from gencoord.sweep.spec import Sweep

FORMAT = "gencoord-sweep-table 1"


def _flag(value: bool) -> str:
    return "1" if value else "0"


def _settings(sweep: Sweep, model_name: str, build: str, banner: str) -> list[str]:
    record = sweep.record
    lines = [f"build {build}", f"model {model_name}", f"integrator {sweep.integrator}",
             f"dt {sweep.dt!r}", f"t_end {sweep.t_end!r}", f"steps {sweep.steps}",
             f"chunk {sweep.chunk}", f"method {sweep.method}",
             f"record_final_state {_flag(record.final_state)}",
             f"record_energy_drift {_flag(record.energy_drift)}",
             f"record_event_time {_flag(record.event_time)}",
             f"trajectory_every {record.trajectory_every}"]
    if sweep.seed is not None:
        lines.append(f"seed {sweep.seed}")
    if sweep.method == "grid":
        lines.append("grid_points " + " ".join(str(len(v.values)) for v in sweep.variables))
    if sweep.event:
        lines += [f"event_stop {_flag(sweep.event.stop)}",
                  "event_text " + " ".join(sweep.event.text.split())]
        for clause in sweep.event.clauses:
            lines.append(f"event_clause {clause.kind} {clause.coordinate or '-'} "
                         f"{_flag(clause.absolute)} {clause.op} {clause.value!r}")
    lines += [f"parameter {name} {value!r}" for name, value in sweep.parameters.items()]
    for kind in ("q", "v"):
        lines += [f"initial {kind} {name} {value!r}"
                  for name, value in sweep.initial[kind].items()]
    lines.append(f"sweep_file {os.path.abspath(sweep.source.path)}")
    lines += [f"sweep_line {line}" for line in sweep.source.text.splitlines()]
    lines += [f"banner_line {line}" for line in banner.splitlines()]
    lines += [f"column {v.kind} {v.name}" for v in sweep.variables]
    return lines


def table_text(sweep: Sweep, model_name: str, build: str, banner: str) -> str:
    """The whole table, digest included."""
    body = "\n".join(_settings(sweep, model_name, build, banner)) + "\n"
    body += f"samples {sweep.count}\n"
    body += "".join(" ".join(map(repr, row)) + "\n" for row in rows(sweep))
    digest = hashlib.sha256(body.encode()).hexdigest()
    return f"{FORMAT}\ndigest {digest}\n{body}"


def write_table(path: str, text: str) -> None:
    """Writes the table whole or not at all (a temporary, then a rename)."""
    partial = path + ".partial"
    with open(partial, "w", encoding="utf-8") as handle:
        handle.write(text)
    os.replace(partial, path)
