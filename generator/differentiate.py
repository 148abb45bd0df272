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
    wanted = {symbol for symbol, _ in replacements} | set(variables)
    definitions: list[tuple[sp.Symbol, sp.Expr]] = []
    jacobian = [[sp.Integer(0)] * len(variables) for _ in outputs]
    gradients: dict[sp.Expr, dict[sp.Symbol, sp.Expr]] = {}  # each expression's, once

    def gradient(expr: sp.Expr) -> dict[sp.Symbol, sp.Expr]:
        if expr not in gradients:
            present = sorted(expr.free_symbols & wanted, key=sp.default_sort_key)
            gradients[expr] = termwise_gradient(expr, present)
        return gradients[expr]

    def derivative(expr: sp.Expr, variable: sp.Symbol, known: dict) -> sp.Expr:
        partials = gradient(expr)
        terms = [partials[variable]] if variable in partials else []
        terms += [known[s] if d == 1 else d * known[s]  # x = y + ... passes dy on as is
                  for s, d in partials.items() if s in known]
        return terms[0] if len(terms) == 1 else sp.Add(*terms)

    reads = [expr.free_symbols & wanted for _, expr in replacements]
    # only the intermediates the outputs read, directly or not, need derivatives
    needed = set().union(*(output.free_symbols & wanted for output in outputs))
    for (symbol, _), present in reversed(list(zip(replacements, reads))):
        if symbol in needed:
            needed |= present
    program = [(assignment, present) for assignment, present in zip(replacements, reads)
               if assignment[0] in needed]
    for j, variable in enumerate(variables):
        known: dict[sp.Symbol, sp.Expr] = {}  # d tmp / d variable, only where nonzero
        for (symbol, expr), present in program:
            if variable not in present and known.keys().isdisjoint(present):
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


def partial(expr: sp.Expr, variable: sp.Symbol) -> sp.Expr:
    """d expr / d variable by the sum, product, power and chain rules.

    SymPy's `diff` spends about a millisecond per call on bookkeeping; the generator takes
    tens of thousands of derivatives of small expressions. Anything beyond +, *, constant
    powers, sin and cos is left to `diff`.
    """
    if expr == variable:
        return sp.Integer(1)
    if expr.is_Atom or variable not in expr.free_symbols:
        return sp.Integer(0)
    if expr.is_Add:
        return sp.Add(*[partial(term, variable) for term in expr.args])
    if expr.is_Mul:
        factors = expr.args
        terms = []
        for k, factor in enumerate(factors):
            d = partial(factor, variable)
            if d != 0:
                terms.append(sp.Mul(*factors[:k], d, *factors[k + 1:]))
        return sp.Add(*terms)
    if expr.is_Pow and variable not in expr.exp.free_symbols:
        base, exponent = expr.args
        return exponent * base**(exponent - 1) * partial(base, variable)
    if isinstance(expr, sp.sin):
        return sp.cos(expr.args[0]) * partial(expr.args[0], variable)
    if isinstance(expr, sp.cos):
        return -sp.sin(expr.args[0]) * partial(expr.args[0], variable)
    return expr.diff(variable)


def termwise_gradient(expr: sp.Expr, variables: list[sp.Symbol]) -> dict[sp.Symbol, sp.Expr]:
    """The nonzero d expr / d w for each w in `variables`, differentiating a sum term by term.

    Each term is differentiated only by the variables it contains: a chain's x_k has k
    terms with one angle each, so its gradient costs k derivatives instead of k * n.
    """
    wanted = set(variables)
    parts: dict[sp.Symbol, list[sp.Expr]] = {}
    for term in (expr.args if expr.is_Add else (expr,)):
        for variable in term.free_symbols & wanted:
            parts.setdefault(variable, []).append(partial(term, variable))
    gradient = {w: sp.Add(*parts[w]) for w in variables if w in parts}
    return {w: d for w, d in gradient.items() if d != 0}


def termwise_jacobian(vector: sp.Matrix, variables: list[sp.Symbol]) -> sp.Matrix:
    """vector.jacobian(variables), computed with `termwise_gradient` row by row."""
    result = sp.zeros(len(vector), len(variables))
    column = {w: j for j, w in enumerate(variables)}
    for i, component in enumerate(vector):
        for w, d in termwise_gradient(component, variables).items():
            result[i, column[w]] = d
    return result
