# SPDX-License-Identifier: BSD-3-Clause
"""Forward-mode differentiation through CSE'd code: Jacobians that reuse the intermediates.

Differentiating the flattened output expressions repeats every shared subexpression in
every derivative (the 20-link chain's residual Jacobians took 90 s that way). Instead, walk
the intermediates tmp_k = e_k(tmp_<k, inputs) once per variable w, applying the chain rule

    d tmp_k / dw = de_k/dw + sum_m de_k/dtmp_m * d tmp_m / dw

where each e_k is small. Each nonzero derivative that is not already a symbol or a number
becomes a new intermediate, so the Jacobian code shares everything the value code computes.
"""

from __future__ import annotations

from typing import Iterator, Union

import sympy as sp


class ChainSum:
    """A derivative the chain rule assembled: sum of factor * d(tmp)/dw terms, kept unexpanded.

    forward_derivatives builds tens of thousands of these, and each is only printed, counted
    and scanned for the symbols it reads; letting SymPy canonicalize every product and sum
    was half the optimize stage. `terms` are (factor, symbol) pairs meaning factor * symbol,
    or (expr, None) meaning expr itself; the factors are shared gradient entries, so the
    printer prints each once (cxx/printer.py).
    """

    __slots__ = ("terms", "free_symbols")
    is_Symbol = is_Number = False  # what forward_derivatives asks of a derivative

    def __init__(self, terms: list[tuple[sp.Expr, sp.Symbol | None]], free_symbols: set):
        self.terms = tuple(terms)
        self.free_symbols = frozenset(free_symbols)

    def as_expr(self) -> sp.Expr:
        """The same value as one SymPy expression (tests and debugging)."""
        return sp.Add(*[factor if symbol is None else factor * symbol
                        for factor, symbol in self.terms])


Derivative = Union[sp.Expr, ChainSum]


class _ForwardMode:
    """The chain rule over one program of intermediates, shared by every pass over it: each
    intermediate's gradient is taken once, whichever variables or directions follow."""

    def __init__(self, replacements: list[tuple[sp.Symbol, sp.Expr]],
                 outputs: list[sp.Expr], inputs: set[sp.Symbol],
                 temporaries: Iterator[sp.Symbol]):
        self.outputs, self.temporaries = outputs, temporaries
        self.wanted = {symbol for symbol, _ in replacements} | inputs
        self.named = {expr: symbol for symbol, expr in replacements
                      if isinstance(expr, (sp.sin, sp.cos))}
        self.definitions: list[tuple[sp.Symbol, Derivative]] = []
        self.gradients: dict[sp.Expr, dict[sp.Symbol, sp.Expr]] = {}  # each expression's
        self.free_of: dict[sp.Expr, frozenset] = {}  # free_symbols_of's, for the entries'
        reads = [expr.free_symbols & self.wanted for _, expr in replacements]
        # only the intermediates the outputs read, directly or not, need derivatives
        needed = set().union(*(output.free_symbols & self.wanted for output in outputs))
        for (symbol, _), present in reversed(list(zip(replacements, reads))):
            if symbol in needed:
                needed |= present
        self.program = [(assignment, present) for assignment, present
                        in zip(replacements, reads) if assignment[0] in needed]
        # the statements reading each symbol: a pass visits only those its seeds reach, so
        # the derivatives by each of the maximal model's 2 nx inputs take O(1) each, not O(n)
        self.readers: dict[sp.Symbol, list[int]] = {}
        for k, (_, present) in enumerate(self.program):
            for symbol in present:
                self.readers.setdefault(symbol, []).append(k)

    def gradient(self, expr: sp.Expr) -> dict[sp.Symbol, sp.Expr]:
        if expr not in self.gradients:
            present = sorted(expr.free_symbols & self.wanted, key=sp.default_sort_key)
            self.gradients[expr] = termwise_gradient(expr, present, self.named)
        return self.gradients[expr]

    def derivative(self, expr: sp.Expr, variable: sp.Symbol | None, known: dict) -> Derivative:
        """d expr / d variable given the derivatives `known` of the symbols it reads; with
        `variable` None, the derivative along the direction that `known` seeds."""
        partials = self.gradient(expr)
        factors: dict[sp.Symbol | None, sp.Expr] = (  # symbol -> its factor; None: the rest
            {None: partials[variable]} if variable in partials else {})
        for s, d in partials.items():
            if s in known:
                dv = known[s]
                if dv.is_Number:
                    d, dv = d * dv, None
                # two intermediates with the same derivative: one term, which may cancel
                factors[dv] = factors[dv] + d if dv in factors else d
        terms = [(d, symbol) for symbol, d in factors.items() if d != 0]
        if not terms:
            return sp.Integer(0)
        if len(terms) == 1:
            factor, symbol = terms[0]
            if symbol is None:
                return factor
            if factor == 1:  # x = y + ... passes dy on as is
                return symbol
        free: set[sp.Symbol] = set()
        for factor, symbol in terms:
            free |= free_symbols_of(factor, self.free_of)
            if symbol is not None:
                free.add(symbol)
        return ChainSum(terms, free)

    def reached(self, seeds: list) -> list[int]:
        """The statements that read the seeds, directly or not, in program order."""
        reached: set[int] = set()
        stack = [k for seed in seeds for k in self.readers.get(seed, ())]
        while stack:
            k = stack.pop()
            if k not in reached:
                reached.add(k)
                stack.extend(self.readers.get(self.program[k][0][0], ()))
        return sorted(reached)

    def sweep(self, variable: sp.Symbol | None, known: dict) -> list[Derivative]:
        """One forward pass: the outputs' derivatives, the new intermediates appended to
        `definitions`; `known` holds the seeds and grows by each nonzero derivative."""
        for k in self.reached([variable, *known]):
            (symbol, expr), present = self.program[k]
            if variable not in present and known.keys().isdisjoint(present):
                continue
            d = self.derivative(expr, variable, known)
            if d == 0:
                continue
            if d.is_Symbol or d.is_Number:
                known[symbol] = d
            else:
                name = next(self.temporaries)
                self.definitions.append((name, d))
                known[symbol] = name
        return [self.derivative(output, variable, known) for output in self.outputs]


def forward_derivatives(replacements: list[tuple[sp.Symbol, sp.Expr]],
                        outputs: list[sp.Expr], variables: list[sp.Symbol],
                        temporaries: Iterator[sp.Symbol]
                        ) -> tuple[list[tuple[sp.Symbol, Derivative]], list[list[Derivative]]]:
    """Derivatives of `outputs` (written in terms of the `replacements` intermediates).

    Returns (new intermediates to append after `replacements`, in dependency order, and
    jacobian[i][j] = d outputs[i] / d variables[j] in terms of all intermediates).
    """
    mode = _ForwardMode(replacements, outputs, set(variables), temporaries)
    columns = [mode.sweep(variable, {}) for variable in variables]
    jacobian = [[column[i] for column in columns] for i in range(len(outputs))]
    return mode.definitions, jacobian


def directional_derivatives(replacements: list[tuple[sp.Symbol, sp.Expr]],
                            outputs: list[sp.Expr], seeds: dict[sp.Symbol, sp.Expr],
                            temporaries: Iterator[sp.Symbol]
                            ) -> tuple[list[tuple[sp.Symbol, Derivative]], list[Derivative]]:
    """The derivatives of `outputs` along a direction: sum over w of d outputs / dw times
    seeds[w], in one pass (J times a vector, for the cost of about one evaluation).

    The seeds are symbols or numbers (the direction's entries, kernel inputs). Returns the
    new intermediates, as forward_derivatives does, and one derivative per output.
    """
    mode = _ForwardMode(replacements, outputs, set(seeds), temporaries)
    return mode.definitions, mode.sweep(None, dict(seeds))


def free_symbols_of(expr: sp.Expr, memo: dict) -> frozenset:
    """expr.free_symbols, kept in `memo` for every subexpression: SymPy computes the property
    from the leaves on each access, so asking it at every level of a recursion over an
    expression costs its size times its depth."""
    found = memo.get(expr)
    if found is None:
        if expr.is_Symbol:
            found = frozenset((expr,))
        elif expr.is_Add or expr.is_Mul or expr.is_Pow or expr.is_Function:
            found = frozenset().union(*(free_symbols_of(arg, memo) for arg in expr.args))
        else:  # numbers, and forms with bound variables, whose own rule SymPy knows
            found = frozenset(expr.free_symbols)
        memo[expr] = found
    return found


def partial(expr: sp.Expr, variable: sp.Symbol, named: dict | None = None,
            memo: dict | None = None) -> sp.Expr:
    """d expr / d variable by the sum, product, power and chain rules.

    SymPy's `diff` spends about a millisecond per call on bookkeeping; the generator takes
    tens of thousands of derivatives of small expressions. Anything beyond +, *, constant
    powers, sin and cos is left to `diff`. `named` maps expressions the code already computes
    to their intermediates: the derivative of sin(q) reads cos(q)'s instead of calling cos again.
    `memo` keeps the subexpressions' free symbols (free_symbols_of) between calls on the same
    expression.
    """
    named = named or {}
    memo = {} if memo is None else memo
    if expr == variable:
        return sp.Integer(1)
    if expr.is_Atom or variable not in free_symbols_of(expr, memo):
        return sp.Integer(0)
    if expr.is_Add:
        return sp.Add(*[partial(term, variable, named, memo) for term in expr.args])
    if expr.is_Mul:
        factors = expr.args
        terms = []
        for k, factor in enumerate(factors):
            d = partial(factor, variable, named, memo)
            if d != 0:
                terms.append(sp.Mul(*factors[:k], d, *factors[k + 1:]))
        return sp.Add(*terms)
    if expr.is_Pow and variable not in free_symbols_of(expr.exp, memo):
        base, exponent = expr.args
        return exponent * base**(exponent - 1) * partial(base, variable, named, memo)
    if isinstance(expr, sp.sin):
        cosine = sp.cos(expr.args[0])
        return named.get(cosine, cosine) * partial(expr.args[0], variable, named, memo)
    if isinstance(expr, sp.cos):
        sine = sp.sin(expr.args[0])
        return -named.get(sine, sine) * partial(expr.args[0], variable, named, memo)
    if isinstance(expr, sp.Abs):
        # every value in the generated code is real, intermediates too: d|u| = u / |u| du
        # (SymPy's diff allows a complex u and leaves derivatives of re(u) and im(u))
        argument = expr.args[0]
        return argument / expr * partial(argument, variable, named, memo)
    return expr.diff(variable)


def termwise_gradient(expr: sp.Expr, variables: list[sp.Symbol],
                      named: dict | None = None) -> dict[sp.Symbol, sp.Expr]:
    """The nonzero d expr / d w for each w in `variables`, differentiating a sum term by term.

    Each term is differentiated only by the variables it contains: a chain's x_k has k
    terms with one angle each, so its gradient costs k derivatives instead of k * n.
    """
    wanted = set(variables)
    parts: dict[sp.Symbol, list[sp.Expr]] = {}
    memo: dict = {}
    for term in (expr.args if expr.is_Add else (expr,)):
        for variable in free_symbols_of(term, memo) & wanted:
            parts.setdefault(variable, []).append(partial(term, variable, named, memo))
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
