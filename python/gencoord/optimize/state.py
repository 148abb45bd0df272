# SPDX-License-Identifier: BSD-3-Clause
"""The state the optimizer's stages (optimize/optimizer.py) hand on, and the options they share."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Iterator

import sympy as sp

from gencoord.cxx.printer import ScalarCxxPrinter
from gencoord.derive.dense import Derivation
from gencoord.cxx.kernel_code import KernelCode
from gencoord.derive.kernel_set import Kernel
from gencoord.optimize.opcount import count_ops
from gencoord.optimize.program import Program
from gencoord.options import GenerateOptions

# (row, column, derivative) of each entry of one Jacobian block
JacobianEntries = list[tuple[int, int, sp.Expr]]


@dataclass(frozen=True)
class OptimizeOptions:
    """Kernels over `max_part_statements` statements (0: none) are cut into parts
    (split.py); with `always_parts` every kernel with a statement is at least one part.
    Matrix outputs with `zero_fill_min` zeros or more are zero-filled (kernel_writer.py)."""
    max_part_statements: int = GenerateOptions.part_statements
    always_parts: bool = False
    zero_fill_min: int = GenerateOptions.zero_fill_min


@dataclass(frozen=True)
class InputIndex:
    """Where each coordinate, rate and acceleration symbol sits in q, v and qdd, and the
    parameters in declaration order."""
    q: dict[sp.Symbol, int]
    v: dict[sp.Symbol, int]
    a: dict[sp.Symbol, int]
    params: list[sp.Symbol]

    @classmethod
    def of(cls, d: Derivation) -> InputIndex:
        return cls({s: i for i, s in enumerate(d.q)}, {s: i for i, s in enumerate(d.v)},
                   {s: i for i, s in enumerate(d.a)}, list(d.params))


@dataclass
class PrintedProgram:
    """The program's C++: every symbol's spelling (tmpN included), each intermediate's
    code and op count, and the outputs' on demand (kernels share outputs: Mt in three)."""
    names: dict[sp.Symbol, str]
    printer: ScalarCxxPrinter
    temporaries: list[str]
    temporary_ops: list[int]
    _outputs: dict[sp.Expr, str] = field(default_factory=dict)
    _output_ops: dict[sp.Expr, int] = field(default_factory=dict)

    def output(self, expr: sp.Expr) -> str:
        if expr not in self._outputs:
            self._outputs[expr] = self.printer.expression(expr)
        return self._outputs[expr]

    def ops(self, expr: sp.Expr) -> int:
        if expr not in self._output_ops:
            self._output_ops[expr] = count_ops(expr)
        return self._output_ops[expr]


@dataclass
class Optimization:
    """What the stages know so far; each stage fills the fields after its own line."""
    # the input: kernels, C++ spellings, the argument each input symbol comes from
    kernels: list[Kernel]
    names: dict[sp.Symbol, str]
    input_of: dict[sp.Symbol, str]
    definitions: Program
    inputs: InputIndex
    # collect_expressions: distinct expressions, definitions first, outputs from first_output
    expressions: list[sp.Expr] = field(default_factory=list)
    index_of: dict[sp.Expr, int] = field(default_factory=dict)
    first_output: int = 0
    # eliminate_common_subexpressions: intermediates in dependency order, reduced expressions
    temporaries: Iterator[sp.Symbol] | None = None
    program: Program = field(default_factory=list)
    reduced: list[sp.Expr] = field(default_factory=list)
    # differentiate_jacobians: each Jacobian or directional-derivative block's entries, by
    # id(block)
    jacobians: dict[int, JacobianEntries] = field(default_factory=dict)
    # print_program
    printed: PrintedProgram | None = None
    # write_kernels
    codes: list[KernelCode] = field(default_factory=list)
