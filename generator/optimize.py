"""One common-subexpression elimination over every output of a model, then per-kernel code.

All kernels' expressions go through a single `sympy.cse` call, so a term shared by the mass
matrix, the forces and the energy is found once and named once (`tmpN`). Each kernel then
keeps only the intermediates its own outputs need, in dependency order.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from .cxx_printer import ScalarCxxPrinter, math_functions_used
from .derive import Derivation
from .differentiate import forward_derivatives
from .kernels import Kernel


@dataclass
class KernelCode:
    """A kernel ready for the template: C++ expressions as strings."""
    kernel: Kernel
    coordinates: list[tuple[str, int]]     # (local name, index into q)
    rates: list[tuple[str, int]]           # (local name, index into v)
    accelerations: list[tuple[str, int]]   # (local name, index into qdd)
    parameters: list[str]                  # parameters read from params
    used_inputs: set[str]                  # the kernel inputs its expressions read
    using: list[str]                       # math functions to bring in with using std::
    intermediates: list[tuple[str, str]]   # (tmp name, C++ expression)
    assignments: list[tuple[str, str]]     # (C++ lvalue, C++ expression)
    mirrors: list[tuple[str, str]]         # (upper lvalue, lower lvalue) of symmetric blocks
    ops: int


@dataclass
class OptimizedModel:
    kernels: list[KernelCode]
    total_ops: int                 # over the shared intermediates and all outputs
    intermediate_count: int
    output_count: int


def _lvalue(block, i: int, j: int) -> str:
    if block.is_scalar:
        return block.name
    if block.array:
        return f"{block.name}[{i}]"
    if block.shape[1] == 1:
        return f"{block.name}({i})"
    return f"{block.name}({i}, {j})"


def optimize(d: Derivation, kernels: list[Kernel], names: dict[sp.Symbol, str],
             input_of: dict[sp.Symbol, str]) -> OptimizedModel:
    """One CSE over all kernels' outputs.

    `names` maps every input and parameter symbol to its C++ spelling; `input_of` maps each
    input symbol to the kernel argument it comes from ("q", "pos", "kappa", ...).
    """
    # one list of distinct expressions, in kernel order, so the result is deterministic
    index_of: dict[sp.Expr, int] = {}
    expressions: list[sp.Expr] = []

    def add(expr: sp.Expr) -> None:
        if expr not in index_of:
            index_of[expr] = len(expressions)
            expressions.append(expr)

    for kernel in kernels:
        for block in kernel.blocks:
            for _, _, expr in block.entries:
                add(expr)
            if block.jacobian_of:
                for expr in block.jacobian_of[0]:
                    add(expr)

    temporaries = sp.numbered_symbols("tmp")
    replacements, reduced = sp.cse(expressions, symbols=temporaries, order="canonical")
    # Jacobian blocks: differentiate the CSE'd code, appending derivative intermediates
    outputs_of: dict[int, list[tuple[int, int, sp.Expr]]] = {}
    for kernel in kernels:
        for block in kernel.blocks:
            if block.jacobian_of:
                of, wrt = block.jacobian_of
                definitions, jacobian = forward_derivatives(
                    replacements, [reduced[index_of[e]] for e in of], wrt, temporaries)
                replacements = replacements + definitions
                outputs_of[id(block)] = [(i, j, jacobian[i][j]) for i in range(len(of))
                                         for j in range(len(wrt))]
    position = {symbol: k for k, (symbol, _) in enumerate(replacements)}
    depends = [[s for s in expr.free_symbols if s in position] for _, expr in replacements]

    all_names = dict(names)
    all_names.update({symbol: symbol.name for symbol, _ in replacements})
    printer = ScalarCxxPrinter(all_names)
    printed_temporaries = [printer.expression(expr) for _, expr in replacements]
    ops_temporaries = [sp.count_ops(expr) for _, expr in replacements]
    q_index = {s: i for i, s in enumerate(d.q)}
    v_index = {s: i for i, s in enumerate(d.v)}
    a_index = {s: i for i, s in enumerate(d.a)}

    codes = []
    for kernel in kernels:
        outputs = [(block, i, j, expr) for block in kernel.blocks
                   for i, j, expr in (outputs_of[id(block)] if block.jacobian_of else
                                      [(i, j, reduced[index_of[e]]) for i, j, e in block.entries])]
        # the intermediates this kernel needs: closure over dependencies
        needed: set[int] = set()
        stack = [position[s] for *_, expr in outputs for s in expr.free_symbols if s in position]
        while stack:
            k = stack.pop()
            if k not in needed:
                needed.add(k)
                stack.extend(position[s] for s in depends[k])
        order = sorted(needed)
        free = set()
        for k in order:
            free |= replacements[k][1].free_symbols
        for *_, expr in outputs:
            free |= expr.free_symbols
        intermediates = [(replacements[k][0].name, printed_temporaries[k]) for k in order]
        assignments = [(_lvalue(block, i, j), printer.expression(expr))
                       for block, i, j, expr in outputs]
        mirrors = [(_lvalue(block, j, i), _lvalue(block, i, j))
                   for block in kernel.blocks if block.symmetric
                   for i, j, _ in block.entries if i != j]
        code_lines = [c for _, c in intermediates] + [c for _, c in assignments]
        codes.append(KernelCode(
            kernel=kernel,
            coordinates=sorted(((names[s], q_index[s]) for s in free if s in q_index),
                               key=lambda pair: pair[1]),
            rates=sorted(((names[s], v_index[s]) for s in free if s in v_index),
                         key=lambda pair: pair[1]),
            accelerations=sorted(((names[s], a_index[s]) for s in free if s in a_index),
                                 key=lambda pair: pair[1]),
            parameters=[names[s] for s in d.params if s in free],
            used_inputs={input_of[s] for s in free if s in input_of},
            using=math_functions_used(code_lines),
            intermediates=intermediates,
            assignments=assignments,
            mirrors=mirrors,
            ops=sum(ops_temporaries[k] for k in order)
            + sum(sp.count_ops(expr) for *_, expr in outputs)))

    derivative_outputs = [expr for entries in outputs_of.values() for *_, expr in entries]
    total = sum(ops_temporaries) + sum(sp.count_ops(expr)
                                       for expr in [*reduced, *derivative_outputs])
    return OptimizedModel(codes, total, len(replacements),
                          len(expressions) + len(derivative_outputs))
