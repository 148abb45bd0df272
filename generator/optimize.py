"""One common-subexpression elimination over every output of a model, then per-kernel code.

All kernels' expressions go through a single `sympy.cse` call, so a term shared by the mass
matrix, the forces and the energy is found once and named once (`tmpN`). Each kernel then
keeps only the intermediates its own outputs need, in dependency order.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from .cxx_printer import ScalarCxxPrinter, math_functions_used
from .derive import Derivation
from .differentiate import forward_derivatives
from .kernels import Kernel
from .opcount import count_ops
from .program import Program, dependency_order, final_names, without_aliases
from .split import MAX_PART_STATEMENTS, plan_parts


@dataclass
class InputsRead:
    """What straight-line code reads: a whole kernel's, or one part's of a long one."""
    coordinates: list[tuple[str, int]]     # (local name, index into q)
    rates: list[tuple[str, int]]           # (local name, index into v)
    accelerations: list[tuple[str, int]]   # (local name, index into qdd)
    parameters: list[str]                  # parameters read from params
    used_inputs: set[str]                  # the kernel inputs its expressions read
    using: list[str]                       # math functions to bring in with using std::


@dataclass
class KernelPart(InputsRead):
    """Statements of a long kernel emitted as a function of their own (split.py).

    `lines` is its code in order: (True, name, C++) defines a local `const Scalar name`,
    (False, lvalue, C++) assigns; the `carried` array's loads and stores are among them.
    """
    lines: list[tuple[bool, str, str]]
    uses_carried: bool
    outputs: set[str]                      # the output blocks it assigns
    # (local, source) of each Eigen output it writes through a raw pointer: lines assign
    # `local[i + rows * j]` (_element)
    data_pointers: list[tuple[str, str]] = field(default_factory=list)
    group: int | None = None               # its translation unit's part group, if any


@dataclass
class KernelCode(InputsRead):
    """A kernel ready for the template: C++ expressions as strings."""
    kernel: Kernel
    intermediates: list[tuple[str, str]]   # (tmp name, C++ expression)
    assignments: list[tuple[str, str]]     # (C++ lvalue, C++ expression)
    mirrors: list[tuple[str, str]]         # (upper lvalue, lower lvalue) of symmetric blocks
    ops: int
    parts: list[KernelPart]                # empty unless the kernel is split (split.py)
    carried_slots: int                     # size of the array the parts exchange values in


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


def _data_pointer(block) -> tuple[str, str]:
    """(local, source) of the raw pointer a part writes an Eigen output block through."""
    if block.name.startswith("(*"):  # an out-parameter, (*dr_dq)
        return f"{block.name[2:-1]}_data", f"{block.name[2:-1]}->data()"
    return f"{block.name}_data", f"{block.name}.data()"


def _writes_through_pointer(block) -> bool:
    return not (block.is_scalar or block.array)


def _element(block, i: int, j: int) -> str:
    """The lvalue of entry (i, j) of `block` in a part: the column-major element through its
    data pointer, not Eigen's operator(). GCC then has no call to resolve and inline per
    statement, which takes about a tenth off compiling a 50-link chain's parts."""
    if not _writes_through_pointer(block):
        return _lvalue(block, i, j)
    local = _data_pointer(block)[0]
    if block.shape[1] == 1:
        return f"{local}[{i}]"
    return f"{local}[{i} + {block.shape[0]} * {j}]"


def optimize(d: Derivation, kernels: list[Kernel], names: dict[sp.Symbol, str],
             input_of: dict[sp.Symbol, str],
             definitions: Program = (),
             max_part_statements: int = MAX_PART_STATEMENTS,
             always_parts: bool = False) -> OptimizedModel:
    """One CSE over all kernels' outputs and the intermediates they are written in.

    `names` maps every input and parameter symbol to its C++ spelling; `input_of` maps each
    input symbol to the kernel argument it comes from ("q", "pos", "kappa", ...);
    `definitions` are the named intermediates the outputs may read (structured.py); kernels
    over `max_part_statements` statements (0: none) are cut into parts (split.py); with
    `always_parts` every kernel with a statement is at least one part.
    """
    # one list of distinct expressions, in kernel order, so the result is deterministic
    index_of: dict[sp.Expr, int] = {}
    expressions: list[sp.Expr] = []

    def add(expr: sp.Expr) -> None:
        if expr not in index_of:
            index_of[expr] = len(expressions)
            expressions.append(expr)

    for _, expr in definitions:
        add(expr)
    first_output = len(expressions)  # outputs come after the definitions
    for kernel in kernels:
        for block in kernel.blocks:
            for _, _, expr in block.entries:
                add(expr)
            if block.jacobian_of:
                for expr in block.jacobian_of[0]:
                    add(expr)

    temporaries = sp.numbered_symbols("__c")  # renamed tmp0, tmp1, ... at the end
    replacements, reduced = sp.cse(expressions, symbols=temporaries, order="canonical")
    replacements = dependency_order(
        [(symbol, reduced[index_of[expr]]) for symbol, expr in definitions], replacements)
    replacements, alias = without_aliases(replacements)
    if alias:
        reduced = [expr.xreplace(alias) for expr in reduced]
    # Jacobian blocks: differentiate the CSE'd code, appending derivative intermediates
    outputs_of: dict[int, list[tuple[int, int, sp.Expr]]] = {}
    for kernel in kernels:
        for block in kernel.blocks:
            if block.jacobian_of:
                of, wrt = block.jacobian_of
                new_definitions, jacobian = forward_derivatives(
                    replacements, [reduced[index_of[e]] for e in of], wrt, temporaries)
                replacements = replacements + new_definitions
                pattern = block.pattern or [(i, j) for i in range(len(of))
                                            for j in range(len(wrt))]
                outputs_of[id(block)] = [(k, 0, jacobian[i][j]) if block.pattern else
                                         (i, j, jacobian[i][j])
                                         for k, (i, j) in enumerate(pattern)]
    position = {symbol: k for k, (symbol, _) in enumerate(replacements)}
    depends = [[s for s in expr.free_symbols if s in position] for _, expr in replacements]

    all_names = dict(names)
    all_names.update(final_names(replacements))  # tmp0, tmp1, ... in program order
    printer = ScalarCxxPrinter(all_names)
    printed_temporaries = [printer.expression(expr) for _, expr in replacements]
    ops_temporaries = [count_ops(expr) for _, expr in replacements]
    printed_outputs: dict[sp.Expr, str] = {}  # kernels share outputs (Mt in three of them)
    ops_outputs: dict[sp.Expr, int] = {}

    def printed(expr: sp.Expr) -> str:
        if expr not in printed_outputs:
            printed_outputs[expr] = printer.expression(expr)
        return printed_outputs[expr]

    def ops(expr: sp.Expr) -> int:
        if expr not in ops_outputs:
            ops_outputs[expr] = count_ops(expr)
        return ops_outputs[expr]
    q_index = {s: i for i, s in enumerate(d.q)}
    v_index = {s: i for i, s in enumerate(d.v)}
    a_index = {s: i for i, s in enumerate(d.a)}

    def inputs_read(free: set[sp.Symbol]) -> dict:
        """The InputsRead fields (but `using`) of code with these free symbols."""
        return dict(
            coordinates=sorted(((names[s], q_index[s]) for s in free if s in q_index),
                               key=lambda pair: pair[1]),
            rates=sorted(((names[s], v_index[s]) for s in free if s in v_index),
                         key=lambda pair: pair[1]),
            accelerations=sorted(((names[s], a_index[s]) for s in free if s in a_index),
                                 key=lambda pair: pair[1]),
            parameters=[names[s] for s in d.params if s in free],
            used_inputs={input_of[s] for s in free if s in input_of})

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
        # its statements: the intermediates, then the output assignments
        statement_free = ([replacements[k][1].free_symbols for k in order]
                          + [expr.free_symbols for *_, expr in outputs])
        intermediates = [(all_names[replacements[k][0]], printed_temporaries[k])
                         for k in order]
        assignments = [(_lvalue(block, i, j), printed(expr))
                       for block, i, j, expr in outputs]
        mirrored = [(block, i, j) for block in kernel.blocks if block.symmetric
                    for i, j, _ in block.entries if i != j]
        mirrors = [(_lvalue(block, j, i), _lvalue(block, i, j)) for block, i, j in mirrored]
        elements = [_element(block, i, j) for block, i, j, _ in outputs]
        plans, slots = plan_parts(
            [all_names[replacements[k][0]] for k in order] + [None] * len(outputs),
            [{all_names[s] for s in free if s in position} for free in statement_free],
            max_part_statements, always_parts)
        parts = []
        statements = intermediates + assignments
        for plan in plans:
            lines = []
            for k in plan.statements:
                lines += [(True, name, f"carried[{slot}]")
                          for name, slot in plan.loads.get(k, [])]
                if k < len(order):
                    lines.append((True, *statements[k]))
                else:
                    lines.append((False, elements[k - len(order)], statements[k][1]))
                if k in plan.stores:
                    lines.append((False, f"carried[{plan.stores[k]}]", statements[k][0]))
            parts.append(KernelPart(
                **inputs_read(set().union(*(statement_free[k] for k in plan.statements))),
                using=math_functions_used(statements[k][1] for k in plan.statements),
                lines=lines, uses_carried=bool(plan.loads or plan.stores),
                outputs={outputs[k - len(order)][0].name for k in plan.statements
                         if k >= len(order)}))
        if always_parts and parts:
            # compiled with the parts, not in every file that includes the header
            parts[-1].lines += [(False, _element(block, j, i), _element(block, i, j))
                                for block, i, j in mirrored]
            parts[-1].outputs |= {block.name for block, _, _ in mirrored}
            mirrors = []
        for part in parts:
            part.data_pointers = [_data_pointer(block) for block in kernel.blocks
                                  if block.name in part.outputs
                                  and _writes_through_pointer(block)]
        codes.append(KernelCode(
            kernel=kernel,
            **inputs_read(set().union(*statement_free)),
            using=math_functions_used(code for _, code in statements),
            intermediates=intermediates,
            assignments=assignments,
            mirrors=mirrors,
            ops=sum(ops_temporaries[k] for k in order)
            + sum(ops(expr) for *_, expr in outputs),
            parts=parts, carried_slots=slots))

    derivative_outputs = [expr for entries in outputs_of.values() for *_, expr in entries]
    total = sum(ops_temporaries) + sum(ops(expr) for expr in [*reduced[first_output:],
                                                              *derivative_outputs])
    return OptimizedModel(codes, total, len(replacements),
                          len(expressions) - first_output + len(derivative_outputs))
