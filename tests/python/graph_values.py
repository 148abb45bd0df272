# SPDX-License-Identifier: BSD-3-Clause
"""Values of large SymPy expressions in mpmath, each distinct node of their graph once.

A derivation builds its outputs out of shared subexpressions (a product of matrices reuses
its factors' entries), so a robot's dense forms, millions of operations written out as
trees, are tens of thousands of distinct objects. Evaluating each object once, bottom up, is
linear in that graph. Substitution (xreplace, evalf) walks the trees instead, and lambdify
prints them whole; with cse=True it first searches for the sharing that is already there,
which takes minutes under SymPy 1.11.
"""

from __future__ import annotations

from typing import Callable, Iterable, Sequence

import mpmath
import sympy as sp

_FUNCTIONS: dict[type, Callable] = {
    sp.sin: mpmath.sin, sp.cos: mpmath.cos, sp.tan: mpmath.tan, sp.exp: mpmath.exp,
    sp.log: mpmath.log, sp.atan2: mpmath.atan2, sp.asin: mpmath.asin, sp.acos: mpmath.acos,
    sp.atan: mpmath.atan, sp.sinh: mpmath.sinh, sp.cosh: mpmath.cosh, sp.tanh: mpmath.tanh,
    sp.Abs: abs, sp.sign: mpmath.sign,
}


def _number(node: sp.Basic) -> mpmath.mpf:
    """A number node in mpmath's current precision."""
    if node.is_Rational:
        return mpmath.mpf(int(node.p)) / int(node.q)
    if node.is_Float:
        return mpmath.mpf(node)
    if node.is_NumberSymbol:  # pi, E
        return mpmath.mpf(node.evalf(mpmath.mp.dps + 5))
    raise TypeError(f"graph_values: cannot evaluate the number {node!r}")


def _operation(node: sp.Basic) -> Callable:
    """What computes `node` from its arguments' values."""
    if node.is_Add:
        return lambda *terms: mpmath.fsum(terms)
    if node.is_Mul:
        return lambda *factors: mpmath.fprod(factors)
    if node.is_Pow:
        if node.exp.is_Integer:
            power = int(node.exp)
            return lambda base, _: base ** power
        return lambda base, exponent: base ** exponent
    function = _FUNCTIONS.get(node.func)
    if function is None:
        raise TypeError(f"graph_values: cannot evaluate {node.func.__name__} nodes")
    return function


class GraphFunction:
    """The expressions as a function of `arguments` (symbols), returning their values as a
    list of mpmath numbers: the graph is ordered once, bottom up, and each call runs that
    order, computing each distinct node once."""

    def __init__(self, arguments: Sequence[sp.Symbol], expressions: Iterable):
        position = {symbol: k for k, symbol in enumerate(arguments)}
        slots: dict[int, int] = {}  # id(node) -> where its value goes
        self._alive: list[sp.Basic] = []  # keeps the nodes alive, so no id() is reused
        self._symbols: list[tuple[int, int]] = []  # (slot, argument position)
        self._numbers: list[tuple[int, sp.Basic]] = []
        self._steps: list[tuple[int, Callable, tuple[int, ...]]] = []

        def slot_of(root: sp.Basic) -> int:
            stack = [root]
            while stack:  # post-order without recursion: the graphs nest thousands deep
                node = stack[-1]
                if id(node) in slots:
                    stack.pop()
                    continue
                # an argument is a leaf, whatever it is: a symbol, or a mechanics q(t)
                argument = position.get(node)
                pending = [] if argument is not None else [
                    a for a in node.args if id(a) not in slots]
                if pending:
                    stack.extend(pending)
                    continue
                stack.pop()
                slot = slots[id(node)] = len(self._alive)
                self._alive.append(node)
                if argument is not None:
                    self._symbols.append((slot, argument))
                elif node.is_Symbol:
                    raise KeyError(f"graph_values: no value for the symbol {node}")
                elif not node.args:
                    self._numbers.append((slot, node))
                else:
                    self._steps.append((slot, _operation(node),
                                        tuple(slots[id(a)] for a in node.args)))
            return slots[id(root)]

        self._outputs = [slot_of(sp.sympify(e)) for e in expressions]

    def __call__(self, *arguments) -> list[mpmath.mpf]:
        values: list = [None] * len(self._alive)
        for slot, k in self._symbols:
            values[slot] = mpmath.mpmathify(arguments[k])
        for slot, node in self._numbers:
            values[slot] = _number(node)
        for slot, operation, children in self._steps:
            values[slot] = operation(*[values[c] for c in children])
        return [values[slot] for slot in self._outputs]


def graph_values(expressions: Iterable, values: dict) -> list[mpmath.mpf]:
    """The value of each expression in mpmath's current precision, its symbols set by
    `values` (symbol -> number)."""
    return GraphFunction(list(values), expressions)(*values.values())
