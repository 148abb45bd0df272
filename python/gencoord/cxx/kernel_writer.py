# SPDX-License-Identifier: BSD-3-Clause
"""The optimizer's last stage: each kernel's statements, lvalues and parts as C++ strings.

A kernel keeps only the intermediates its own outputs need (the closure over what they
read), in program order; a long kernel is cut into parts (split.py).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import sympy as sp

from gencoord.cxx.composed import composed_body
from gencoord.cxx.printer import math_functions_used
from gencoord.cxx.kernel_code import KernelCode, KernelPart
from gencoord.cxx.sin_cos import batch_sin_cos
from gencoord.derive.kernel_set import Block, Kernel
from gencoord.cxx.lvalues import data_pointer, element, lvalue, target, writes_through_pointer
from gencoord.optimize.state import OptimizeOptions, Optimization
from gencoord.optimize.split import PartPlan, plan_parts

Output = tuple[Block, int, int, sp.Expr]  # (block, row, column, expression)


@dataclass
class _Statements:
    """One kernel's statements: its intermediates, then its output assignments."""
    order: list[int]                 # the intermediates, as indices into the program
    outputs: list[Output]
    free: list[set[sp.Symbol]]       # the symbols each statement reads
    code: list[tuple[str, str]]      # (name or lvalue, C++) of each statement
    elements: list[str]              # each output's lvalue in a part (lvalues.element)


class _KernelWriter:
    """Writes the kernels of one optimized program; knows what each intermediate reads."""

    def __init__(self, work: Optimization, options: OptimizeOptions):
        self.work, self.options = work, options
        assert work.printed is not None  # print_program runs before write_kernels
        self.printed = work.printed
        self.position = {symbol: k for k, (symbol, _) in enumerate(work.program)}
        self.depends = [[s for s in expr.free_symbols if s in self.position]
                        for _, expr in work.program]

    def entries(self, block: Block) -> list[tuple[int, int, sp.Expr]]:
        """The block's entries after the CSE (and forward mode, for a Jacobian)."""
        if block.jacobian_of or block.tangent_of:
            return self.work.jacobians[id(block)]
        return [(i, j, self.work.reduced[self.work.index_of[e]]) for i, j, e in block.entries]

    def kept_entries(self, kernel: Kernel) -> tuple[list, list[Block]]:
        """(block, its entries to assign) of each block, and the zero-filled blocks: the Eigen
        matrices with at least options.zero_fill_min zero entries, whose zeros are not assigned."""
        kept, zero_filled = [], []
        for block in kernel.blocks:
            entries = self.entries(block)
            if (not block.is_scalar and not block.array
                    and sum(expr == 0 for *_, expr in entries) >= self.options.zero_fill_min):
                zero_filled.append(block)
                entries = [entry for entry in entries if entry[2] != 0]
            kept.append((block, entries))
        return kept, zero_filled

    def needed(self, outputs: list[Output]) -> list[int]:
        """The intermediates these outputs need: the closure over dependencies, in order."""
        needed: set[int] = set()
        stack = [self.position[s] for *_, expr in outputs for s in expr.free_symbols
                 if s in self.position]
        while stack:
            k = stack.pop()
            if k not in needed:
                needed.add(k)
                stack.extend(self.position[s] for s in self.depends[k])
        return sorted(needed)

    def statements(self, kept: list) -> _Statements:
        program, printed = self.work.program, self.printed
        outputs = [(block, i, j, expr) for block, entries in kept for i, j, expr in entries]
        order = self.needed(outputs)
        free = ([program[k][1].free_symbols for k in order]
                + [expr.free_symbols for *_, expr in outputs])
        code = ([(printed.names[program[k][0]], printed.temporaries[k]) for k in order]
                + [(lvalue(block, i, j), printed.output(expr))
                   for block, i, j, expr in outputs])
        return _Statements(order, outputs, free, code,
                           [element(block, i, j) for block, i, j, _ in outputs])

    def inputs_read(self, free: set[sp.Symbol]) -> dict:
        """The InputsRead fields (but `using` and `sin_cos`) of code with these free symbols."""
        names, inputs = self.work.names, self.work.inputs

        def indexed(index: dict[sp.Symbol, int]) -> list[tuple[str, int]]:
            return sorted(((names[s], index[s]) for s in free if s in index),
                          key=lambda pair: pair[1])
        return dict(coordinates=indexed(inputs.q), rates=indexed(inputs.v),
                    accelerations=indexed(inputs.a),
                    parameters=[names[s] for s in inputs.params if s in free],
                    used_inputs={self.work.input_of[s] for s in free
                                 if s in self.work.input_of})

    def part(self, plan: PartPlan, s: _Statements) -> KernelPart:
        """One part's lines: its statements with the loads and stores of `carried`."""
        lines = []
        for k in plan.statements:
            lines += [(True, name, f"carried[{slot}]") for name, slot in plan.loads.get(k, [])]
            if k < len(s.order):
                lines.append((True, *s.code[k]))
            else:
                lines.append((False, s.elements[k - len(s.order)], s.code[k][1]))
            if k in plan.stores:
                lines.append((False, f"carried[{plan.stores[k]}]", s.code[k][0]))
        inputs = self.inputs_read(set().union(*(s.free[k] for k in plan.statements)))
        sin_cos, codes = batch_sin_cos([name for name, _ in inputs["coordinates"]],
                                       [code for *_, code in lines])
        lines = [(defines, left, code) for (defines, left, _), code in zip(lines, codes)]
        return KernelPart(
            **inputs, using=math_functions_used(codes), sin_cos=sin_cos,
            lines=lines, uses_carried=bool(plan.loads or plan.stores),
            outputs={s.outputs[k - len(s.order)][0].name for k in plan.statements
                     if k >= len(s.order)})

    def kernel_code(self, kernel: Kernel) -> KernelCode:
        kept, zero_filled = self.kept_entries(kernel)
        s = self.statements(kept)
        names = self.printed.names
        mirrored = [(block, i, j) for block, entries in kept if block.symmetric
                    for i, j, _ in entries if i != j]
        mirrors = [(lvalue(block, j, i), lvalue(block, i, j)) for block, i, j in mirrored]
        plans, slots = plan_parts(
            [names[self.work.program[k][0]] for k in s.order] + [None] * len(s.outputs),
            [{names[symbol] for symbol in free if symbol in self.position} for free in s.free],
            self.options.max_part_statements, self.options.always_parts)
        parts = [self.part(plan, s) for plan in plans]
        if self.options.always_parts and parts:
            # compiled with the parts, not in every file that includes the header
            parts[-1].lines += [(False, element(block, j, i), element(block, i, j))
                                for block, i, j in mirrored]
            parts[-1].outputs |= {block.name for block, _, _ in mirrored}
            mirrors = []
        for part in parts:
            part.data_pointers = [data_pointer(block) for block in kernel.blocks
                                  if block.name in part.outputs
                                  and writes_through_pointer(block)]
        printed = self.printed
        inputs = self.inputs_read(set().union(*s.free))
        sin_cos, codes = ([], [code for _, code in s.code]) if parts else batch_sin_cos(
            [name for name, _ in inputs["coordinates"]], [code for _, code in s.code])
        code = [(left, text) for (left, _), text in zip(s.code, codes)]
        return KernelCode(
            kernel=kernel, **inputs, using=math_functions_used(codes), sin_cos=sin_cos,
            intermediates=code[:len(s.order)], assignments=code[len(s.order):],
            mirrors=mirrors, zero_filled=[target(block) for block in zero_filled],
            ops=sum(printed.temporary_ops[k] for k in s.order)
            + sum(printed.ops(expr) for *_, expr in s.outputs),
            parts=parts, carried_slots=slots)


def looped_kernel_code(kernel: Kernel, ops_of: dict[str, int]) -> KernelCode:
    """A composed kernel (looped.py): its body is calls (composed.py); it reads every input
    it takes (they are passed on) and counts the operations of the calls it makes."""
    assert kernel.composed is not None, kernel.name
    ops = sum(ops_of[name] * times for name, times in kernel.composed.call_counts())
    return KernelCode(kernel=kernel, coordinates=[], rates=[], accelerations=[],
                      parameters=[], used_inputs=set(kernel.inputs), using=[], sin_cos=[],
                      intermediates=[], assignments=[], mirrors=[],
                      ops=ops, parts=[], carried_slots=0, body=composed_body(kernel))


def write_kernels(work: Optimization, options: OptimizeOptions) -> Optimization:
    """Each kernel's code: its statements, mirrored entries and parts; the looped kernels'
    last, as they count the operations of the kernels they call."""
    writer = _KernelWriter(work, options)
    codes = {id(k): writer.kernel_code(k) for k in work.kernels if not k.composed}
    ops_of = {code.kernel.name: code.ops for code in codes.values()}
    for kernel in work.kernels:
        if kernel.composed:
            codes[id(kernel)] = looped_kernel_code(kernel, ops_of)
            ops_of[kernel.name] = codes[id(kernel)].ops
    return replace(work, codes=[codes[id(kernel)] for kernel in work.kernels])
