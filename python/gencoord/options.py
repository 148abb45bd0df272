# SPDX-License-Identifier: BSD-3-Clause
"""Every knob of one generation, in one frozen dataclass: `GenerateOptions`.

The `generate` command line builds one from its flags (and through it `gencoord generate`,
the other `gencoord` commands and CMake's gencoord_add_model, which run it); tests build them
directly. Each field's `help` is what `generate --help` prints for its flag and what
docs/generator.md lists: `python3 -m gencoord.options` prints that table.
"""

from __future__ import annotations

import dataclasses
import math
import shlex
from dataclasses import dataclass
from typing import Any, Callable

DYNAMICS_CHOICES = ("auto", "dense", "recursive")


def _knob(default: Any, help: str, flag: str | None = None, metavar: str | None = None,
          parse: Callable[[str], Any] | None = None):
    """A field with its documentation; `flag` is its command-line option, if it has one,
    whose text `parse` turns into the field's value (a boolean field's flag takes none and
    sets it)."""
    return dataclasses.field(default=default, metadata={"help": help, "flag": flag,
                                                        "metavar": metavar, "parse": parse})


@dataclass(frozen=True)
class GenerateOptions:
    """How one model file is generated. The defaults give the headers in generated/."""

    # The fields with a flag come first, in the order the header's banner repeats them.
    max_part_statements: int | None = _knob(
        None, "emit a kernel of more statements as several functions, which keeps C++ compile "
        "time near linear (default: part_statements, or large_tree_part_statements for a tree "
        "of loop_min_nq coordinates or more; 0: never)",
        "--max-function-statements", "N", int)
    loop_min_nq: int = _knob(
        40, "a tree of N coordinates or more gets Mt, J and the residual Jacobians as loops "
        "over O(nq) products, so that their code grows like nq, not nq^2. Unrolled, the "
        "outputs run faster (composite bodies take O(1) per entry of Mt) and, for a few dozen "
        "coordinates, still generate in seconds; past that their n^2 code dominates",
        "--loop-min-nq", "N", int)
    translation_units: int = _knob(
        0, "compile the kernels for double in N source files of their own "
        "(DIR/<name>_double_K.cpp), which build in parallel; the header declares them extern "
        "template (0: header only)", "--translation-units", "N", int)
    name: str | None = _knob(
        None, "the model's name instead of the file's stem (the header NAME.hpp, the C++ "
        "type; option values are still appended): a C++ identifier", "--name", "NAME", str)
    dynamics: str = _knob(
        "auto", "qddot and inverse_dynamics of a model that is a tree (of particles, or of "
        "bodies joined by joints): by the O(nq) recursions, dense (Mt, Ft + Fi), or auto: "
        "whichever takes fewer operations", "--dynamics", "{auto,dense,recursive}", str)
    load_timeout: float | None = _knob(
        60.0, "stop with an error when running the model file takes longer than this many "
        "seconds of wall-clock time (0: no limit)", "--load-timeout", "SECONDS", float)
    maximal: bool = _knob(
        False, "also generate the model's maximal-coordinate penalty model (the nested struct "
        "Maximal) that `gencoord crosscheck` and the runtime's gencoord/maximal/ headers run. "
        "It is about as large as the reduced model: the 7-joint arm generates in 4 s "
        "of CPU without it, 7 s with it (docs/performance.md)", "--maximal")
    # Knobs without a flag: measured trade-offs (docs/performance.md), fixed for a release.
    flat_max_nq: int = _knob(
        3, "up to this many coordinates every output is one flat expression, which lets SymPy "
        "cancel terms exactly (pendulum_3d's Fi is 0) and differentiate the maximal forces "
        "symbolically; larger models use named intermediates and forward-mode Jacobians")
    part_statements: int = _knob(
        2000, "the longest part of a split kernel by default. Each part passes values through "
        "memory: the 50-link chain's kernels compile in 202 s unsplit, 71 s at 2000, 50 s at "
        "250; the 10-link stiff chain's residual_jacobians runs 12% slower at 2000, 60% at 250 "
        "(g++ 12 -O2)")
    large_tree_part_statements: int = _knob(
        500, "the longest part by default for a tree of loop_min_nq coordinates or more: in "
        "parts of 2000 GCC's time still grows faster than n (28, 94, 278 s at n = 100, 200, "
        "400 against 30, 58, 115 s in parts of 500), and qddot runs as fast")
    zero_fill_min: int = _knob(
        8, "an Eigen matrix output with at least this many zero entries is zero-filled first "
        "and only its nonzero entries are assigned: a chain's Jacobian is half zeros, a legged "
        "robot's mass matrix mostly zeros, and every assignment costs compile time")
    unroll_max_nq: int = _knob(
        6, "qddot's LDL^T solve is written out entry by entry up to this many coordinates "
        "(about nq^3 / 6 lines) and loops beyond: unrolled is about 10% faster at nq = 2 and "
        "5, equal at 10; either is 1.6-2.2x faster than Eigen's fixed-size LLT")

    def __post_init__(self) -> None:
        problems = []
        if self.max_part_statements is not None and self.max_part_statements < 0:
            problems.append("max_part_statements must be 0 (never split) or positive")
        if self.loop_min_nq < 1:
            problems.append("loop_min_nq must be positive")
        if self.translation_units < 0:
            problems.append("translation_units must be 0 (header only) or positive")
        if self.load_timeout is not None and not (0 <= self.load_timeout < math.inf):
            problems.append("load_timeout must be 0 (no limit) or a positive number of seconds")
        if self.dynamics not in DYNAMICS_CHOICES:
            problems.append(f"dynamics must be one of {', '.join(DYNAMICS_CHOICES)}")
        if problems:
            raise ValueError("; ".join(problems))

    def part_statements_for(self, large_tree: bool) -> int:
        """The longest part of a kernel: max_part_statements if given, else the default."""
        if self.max_part_statements is not None:
            return self.max_part_statements
        return self.large_tree_part_statements if large_tree else self.part_statements

    def banner_flags(self) -> list[str]:
        """The flags that regenerate with these options, for the header's banner."""
        flags = []
        if self.max_part_statements is not None:
            flags.append(f"--max-function-statements {self.max_part_statements}")
        if self.loop_min_nq != GenerateOptions.loop_min_nq:
            flags.append(f"--loop-min-nq {self.loop_min_nq}")
        if self.translation_units:
            flags.append(f"--translation-units {self.translation_units}")
        if self.name:
            flags.append("--name " + shlex.quote(self.name))
        if self.dynamics != GenerateOptions.dynamics:
            flags.append("--dynamics " + self.dynamics)
        if self.maximal:
            flags.append("--maximal")
        return flags


def knobs() -> list[dataclasses.Field]:
    return list(dataclasses.fields(GenerateOptions))


def markdown_table() -> str:
    """The table of docs/generator.md: every field, its flag, default and meaning."""
    rows = ["| field | flag | default | meaning |", "|---|---|---|---|"]
    for knob in knobs():
        flag = knob.metadata["flag"]
        metavar = knob.metadata["metavar"]
        flag = f"`{flag} {metavar}`" if metavar else f"`{flag}`" if flag else ""
        rows.append(f"| `{knob.name}` | {flag} | `{knob.default}` | {knob.metadata['help']} |")
    return "\n".join(rows) + "\n"


if __name__ == "__main__":
    print(markdown_table(), end="")
