"""Forward-mode differentiation through CSE'd code: Jacobians that reuse the intermediates.

Differentiating the flattened output expressions repeats every shared subexpression in
every derivative (the 20-link chain's residual Jacobians took 90 s that way). Instead, walk
the intermediates tmp_k = e_k(tmp_<k, inputs) once per variable w, applying the chain rule

    d tmp_k / dw = de_k/dw + sum_m de_k/dtmp_m * d tmp_m / dw

where each e_k is small. Each nonzero derivative that is not already a symbol or a number
becomes a new intermediate, so the Jacobian code shares everything the value code computes.
"""

from __future__ import annotations

from typing import Iterator

import sympy as sp


def forward_derivatives(replacements: list[tuple[sp.Symbol, sp.Expr]],
                        outputs: list[sp.Expr], variables: list[sp.Symbol],
                        temporaries: Iterator[sp.Symbol]
                        ) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[list[sp.Expr]]]:
    """Derivatives of `outputs` (written in terms of the `replacements` intermediates).

    Returns (new intermediates to append after `replacements`, in dependency order, and
    jacobian[i][j] = d outputs[i] / d variables[j] in terms of all intermediates).
    """
    is_temporary = {symbol for symbol, _ in replacements}
    definitions: list[tuple[sp.Symbol, sp.Expr]] = []
    jacobian = [[sp.Integer(0)] * len(variables) for _ in outputs]
    partials: dict[tuple[sp.Expr, sp.Symbol], sp.Expr] = {}  # each de/ds is taken once

    def partial(expr: sp.Expr, symbol: sp.Symbol) -> sp.Expr:
        key = (expr, symbol)
        if key not in partials:
            partials[key] = expr.diff(symbol)
        return partials[key]

    def derivative(expr: sp.Expr, variable: sp.Symbol, known: dict) -> sp.Expr:
        free = expr.free_symbols
        terms = [partial(expr, variable)] if variable in free else []
        terms += [partial(expr, s) * known[s] for s in free if s in is_temporary and s in known]
        return sp.Add(*terms)

    for j, variable in enumerate(variables):
        known: dict[sp.Symbol, sp.Expr] = {}  # d tmp / d variable, only where nonzero
        for symbol, expr in replacements:
            if not (variable in expr.free_symbols
                    or any(s in known for s in expr.free_symbols)):
                continue
            d = derivative(expr, variable, known)
            if d == 0:
                continue
            if d.is_Symbol or d.is_Number:
                known[symbol] = d
            else:
                name = next(temporaries)
                definitions.append((name, d))
                known[symbol] = name
        for i, output in enumerate(outputs):
            jacobian[i][j] = derivative(output, variable, known)
    return definitions, jacobian
