# SPDX-License-Identifier: BSD-3-Clause
"""Straight-line programs `symbol = expr`: merging, alias removal and final naming.

The structured derivation (structured.py) hands the optimizer named intermediates; CSE then
adds its own. These helpers turn both into one list in dependency order, drop names that
only alias a symbol or a number, and give every intermediate its final name tmp0, tmp1, ...
in program order, so the emitted code reads top to bottom.
"""

from __future__ import annotations

import sympy as sp

Program = list[tuple[sp.Symbol, sp.Expr]]


def dependency_order(roots: Program, rest: Program) -> Program:
    """All assignments of `roots` and `rest`, each after the ones it reads.

    A depth-first walk from each root in turn pulls in what it needs just before it; the
    assignments of `rest` nobody needs come last, in their given order. Deterministic.
    """
    nodes = roots + rest
    position = {symbol: k for k, (symbol, _) in enumerate(nodes)}
    reads = [sorted(position[s] for s in expr.free_symbols if s in position)
             for _, expr in nodes]
    done = [False] * len(nodes)
    order = []
    for root in range(len(nodes)):
        stack = [(root, 0)]
        while stack:
            k, i = stack.pop()
            if done[k]:
                continue
            if i < len(reads[k]):
                stack.append((k, i + 1))
                if not done[reads[k][i]]:
                    stack.append((reads[k][i], 0))
            else:
                done[k] = True
                order.append(nodes[k])
    return order


def without_aliases(program: Program) -> tuple[Program, dict[sp.Symbol, sp.Expr]]:
    """Drops assignments of a bare symbol or number; returns the substitution to apply."""
    alias: dict[sp.Symbol, sp.Expr] = {}
    kept = []
    for symbol, expr in program:
        if alias and not expr.free_symbols.isdisjoint(alias):
            expr = expr.xreplace(alias)
        if expr.is_Atom:
            alias[symbol] = expr
        else:
            kept.append((symbol, expr))
    return kept, alias


def final_names(program: Program, prefix: str = "tmp") -> dict[sp.Symbol, str]:
    """The C++ names tmp0, tmp1, ... in program order (the printer maps symbols to them)."""
    return {symbol: f"{prefix}{k}" for k, (symbol, _) in enumerate(program)}
