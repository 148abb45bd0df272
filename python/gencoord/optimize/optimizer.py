# SPDX-License-Identifier: BSD-3-Clause
"""One common-subexpression elimination over every output of a model, then per-kernel code.

All kernels' expressions go through a single `sympy.cse` call, so a term shared by the mass
matrix, the forces and the energy is found once and named once (`tmpN`). Each kernel then
keeps only the intermediates its own outputs need, in dependency order (cxx/kernel_writer.py).

`optimize_model` runs the stages in order; each takes the `Optimization` the one before
returned and the shared `OptimizeOptions`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable, Sequence

import sympy as sp

from gencoord.cxx.printer import ScalarCxxPrinter
from gencoord.derive.dense import Derivation
from gencoord.derive.differentiate import directional_derivatives, forward_derivatives
from gencoord.cxx.kernel_code import KernelCode
from gencoord.derive.kernel_set import Kernel
from gencoord.optimize.opcount import count_ops
from gencoord.optimize.state import InputIndex, OptimizeOptions, Optimization, PrintedProgram
from gencoord.optimize.program import dependency_order, final_names, without_aliases
from gencoord.cxx.kernel_writer import write_kernels

__all__ = ["OptimizeOptions", "OptimizedModel", "optimize_model"]


@dataclass
class OptimizedModel:
    kernels: list[KernelCode]
    total_ops: int                 # over the shared intermediates and all outputs
    intermediate_count: int
    output_count: int


def collect_expressions(work: Optimization, options: OptimizeOptions) -> Optimization:
    """One list of distinct expressions: the definitions, then every kernel's outputs in
    kernel order, so the result is deterministic."""
    index_of: dict[sp.Expr, int] = {}
    expressions: list[sp.Expr] = []

    def add(expr: sp.Expr) -> None:
        if expr not in index_of:
            index_of[expr] = len(expressions)
            expressions.append(expr)

    for _, expr in work.definitions:
        add(expr)
    first_output = len(expressions)
    for kernel in work.kernels:
        for block in kernel.blocks:
            for _, _, expr in block.entries:
                add(expr)
            for differentiated in (block.jacobian_of, block.tangent_of):
                for expr in (differentiated[0] if differentiated else ()):
                    add(expr)
    return replace(work, expressions=expressions, index_of=index_of, first_output=first_output)


def eliminate_common_subexpressions(work: Optimization,
                                    options: OptimizeOptions) -> Optimization:
    """The CSE itself, the definitions merged in dependency order, aliases dropped."""
    temporaries = sp.numbered_symbols("__c")  # renamed tmp0, tmp1, ... when printed
    replacements, reduced = sp.cse(work.expressions, symbols=temporaries, order="canonical")
    replacements = dependency_order(
        [(symbol, reduced[work.index_of[expr]]) for symbol, expr in work.definitions],
        replacements)
    replacements, alias = without_aliases(replacements)
    if alias:
        reduced = [expr.xreplace(alias) for expr in reduced]
    return replace(work, temporaries=temporaries, program=replacements, reduced=reduced)


def differentiate_jacobians(work: Optimization, options: OptimizeOptions) -> Optimization:
    """Jacobian and directional-derivative blocks: forward mode through the CSE'd code,
    appending the derivative intermediates to the program (differentiate.py)."""
    program, jacobians = work.program, {}
    temporaries = work.temporaries
    assert temporaries is not None  # set by eliminate_common_subexpressions, which runs first
    for kernel in work.kernels:
        for block in kernel.blocks:
            differentiated = block.tangent_of or block.jacobian_of
            if not differentiated:
                continue
            of = [work.reduced[work.index_of[e]] for e in differentiated[0]]
            if block.tangent_of:
                new_definitions, along = directional_derivatives(
                    program, of, block.tangent_of[1], temporaries)
                entries = [(i, 0, d) for i, d in enumerate(along)]
            else:
                assert block.jacobian_of is not None  # differentiated, and not a tangent
                wrt = block.jacobian_of[1]
                new_definitions, jacobian = forward_derivatives(program, of, wrt, temporaries)
                pattern = block.pattern or [(i, j) for i in range(len(of))
                                            for j in range(len(wrt))]
                entries = [(k, 0, jacobian[i][j]) if block.pattern else (i, j, jacobian[i][j])
                           for k, (i, j) in enumerate(pattern)]
            program = program + new_definitions
            jacobians[id(block)] = entries
    return replace(work, program=program, jacobians=jacobians)


def print_program(work: Optimization, options: OptimizeOptions) -> Optimization:
    """Final names tmp0, tmp1, ... in program order, each intermediate's C++ and op count."""
    names = dict(work.names)
    names.update(final_names(work.program))
    printer = ScalarCxxPrinter(names)
    printed = PrintedProgram(
        names=names, printer=printer,
        temporaries=[printer.expression(expr) for _, expr in work.program],
        temporary_ops=[count_ops(expr) for _, expr in work.program])
    return replace(work, printed=printed)


STAGES: tuple[Callable[[Optimization, OptimizeOptions], Optimization], ...] = (
    collect_expressions, eliminate_common_subexpressions, differentiate_jacobians,
    print_program, write_kernels)


def summarize(work: Optimization) -> OptimizedModel:
    """The kernels with the whole model's counts: ops, intermediates, outputs."""
    derivative_outputs = [expr for entries in work.jacobians.values() for *_, expr in entries]
    outputs = [*work.reduced[work.first_output:], *derivative_outputs]
    assert work.printed is not None  # set by print_program
    total = (sum(work.printed.temporary_ops)
             + sum(work.printed.ops(expr) for expr in outputs))
    return OptimizedModel(work.codes, total, len(work.program),
                          len(work.expressions) - work.first_output + len(derivative_outputs))


def optimize_model(d: Derivation, kernels: list[Kernel], names: dict[sp.Symbol, str],
                   input_of: dict[sp.Symbol, str],
                   definitions: Sequence[tuple[sp.Symbol, sp.Expr]] = (),
                   options: OptimizeOptions = OptimizeOptions()) -> OptimizedModel:
    """Runs every stage over all kernels' outputs and the intermediates they are written in.

    `names` maps every input and parameter symbol to its C++ spelling; `input_of` maps each
    input symbol to the kernel argument it comes from ("q", "pos", "kappa", ...);
    `definitions` are the named intermediates the outputs may read (structured.py).
    """
    work = Optimization(kernels=kernels, names=names, input_of=input_of,
                        definitions=list(definitions), inputs=InputIndex.of(d))
    for stage in STAGES:
        work = stage(work, options)
    return summarize(work)
