# SPDX-License-Identifier: BSD-3-Clause
"""Prints SymPy expressions as C++ for kernels templated on `Scalar`.

Literals are wrapped as `Scalar(...)` so float, double and autodiff scalars all work, math
functions are printed unqualified (the kernel brings them in with `using std::sin;`, which
keeps argument-dependent lookup open for custom scalars), and small integer powers become
multiplications.
"""

from __future__ import annotations

import re

import sympy as sp
from sympy.printing.cxx import CXX17CodePrinter
from sympy.printing.precedence import precedence

from gencoord.library_versions import code_printer_settings
from gencoord.derive.differentiate import ChainSum

MATH_FUNCTIONS = ("sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh",
                  "exp", "log", "sqrt", "abs", "pow", "cbrt")
_FUNCTION_CALL = re.compile(r"\b(" + "|".join(MATH_FUNCTIONS) + r")\(")


class UnsupportedExpression(Exception):
    """An expression the C++ printer cannot emit (Piecewise, unknown functions ...)."""


class ScalarCxxPrinter(CXX17CodePrinter):
    """C++17 printer whose symbols are renamed through `names`."""

    _ns = ""  # unqualified math functions: see the module docstring

    def __init__(self, names: dict[sp.Symbol, str]):
        # order "none": terms in SymPy's canonical argument order (deterministic) instead of
        # sorted again for display, which doubled the printing time of large models
        super().__init__(code_printer_settings(CXX17CodePrinter, strict=True, order="none"))
        self._names = names
        self._signed_cache: dict[sp.Expr, tuple[bool, str]] = {}

    def _print_Symbol(self, expr):
        try:
            return self._names[expr]
        except KeyError:
            raise UnsupportedExpression(f"symbol {expr} has no C++ name") from None

    def _print_Integer(self, expr):
        return f"Scalar({int(expr)})"

    def _print_Zero(self, expr):
        # StrPrinter's own _print_Zero prints a bare 0 in SymPy 1.11 and below
        return self._print_Integer(expr)

    def _print_Rational(self, expr):
        p, q = int(expr.p), int(expr.q)
        if q & (q - 1) == 0:  # a power of two: the decimal literal is exact
            return f"Scalar({p / q!r})"
        return f"(Scalar({p})/Scalar({q}))"

    def _print_Float(self, expr):
        return f"Scalar({float(expr)!r})"

    def _print_Pow(self, expr):
        base, exponent = expr.base, expr.exp
        b = self.parenthesize(base, precedence(sp.Mul(2, 3, evaluate=False)))
        if exponent.is_Integer:
            n = int(exponent)
            if 2 <= n <= 4:
                return "(" + "*".join([b] * n) + ")"
            if -4 <= n <= -1:
                return "(Scalar(1)/" + ("(" + "*".join([b] * -n) + ")" if n < -1 else b) + ")"
            return f"pow({self._print(base)}, {self._print(exponent)})"
        if exponent == sp.Rational(1, 2):
            return f"sqrt({self._print(base)})"
        if exponent == sp.Rational(-1, 2):
            return f"(Scalar(1)/sqrt({self._print(base)}))"
        if exponent == sp.Rational(-3, 2):
            return f"(Scalar(1)/({b}*sqrt({self._print(base)})))"
        if exponent == sp.Rational(3, 2):
            return f"({b}*sqrt({self._print(base)}))"
        return f"pow({self._print(base)}, {self._print(exponent)})"

    def _print_Abs(self, expr):
        return f"abs({self._print(expr.args[0])})"

    def emptyPrinter(self, expr):
        raise UnsupportedExpression(f"cannot emit {type(expr).__name__} ({expr}) as C++")

    def _print_not_supported(self, expr):
        raise UnsupportedExpression(f"cannot emit {type(expr).__name__} ({expr}) as C++")

    def expression(self, expr) -> str:
        if isinstance(expr, ChainSum):
            return self._chain_sum(expr)
        # doprint walks each whole tree again (re() handling, assignment wrapping) before
        # printing it; kernels of large models print tens of thousands of expressions, so
        # print directly and keep doprint for anything that needs it (constants like pi)
        self._not_supported: set[sp.Basic] = set()
        self._number_symbols: set[tuple[sp.Basic, sp.Basic]] = set()
        text = self._print(expr)
        if self._not_supported or self._number_symbols or "\n" in text or expr.has(sp.re):
            return self.doprint(expr)
        return text

    def _chain_sum(self, expr: ChainSum) -> str:
        """A forward-mode derivative's terms joined as one C++ sum, signs pulled out."""
        text = ""
        for factor, symbol in expr.terms:
            negative, magnitude = self._signed(factor)
            if symbol is not None:
                name = self._print_Symbol(symbol)
                if magnitude == "Scalar(1)":
                    magnitude = name
                elif factor.is_Add:  # never negative: _signed leaves sums whole
                    magnitude = f"({magnitude})*{name}"
                else:
                    magnitude = f"{magnitude}*{name}"
            if not text:
                text = "-" + magnitude if negative else magnitude
            else:
                text += (" - " if negative else " + ") + magnitude
        return text

    def _signed(self, factor: sp.Expr) -> tuple[bool, str]:
        """(is negative, text of its magnitude) of a gradient entry, printed once."""
        if factor not in self._signed_cache:
            negative, magnitude = False, factor
            if factor.is_Number and factor.is_negative:
                negative, magnitude = True, -factor
            elif factor.is_Mul and factor.args[0].is_Number and factor.args[0].is_negative:
                coefficient, rest = factor.args[0], factor.args[1:]
                negative = True
                if coefficient != -1:
                    rest = (-coefficient, *rest)
                magnitude = rest[0] if len(rest) == 1 else sp.Mul._from_args(rest)
            self._signed_cache[factor] = (negative, self.expression(magnitude))
        return self._signed_cache[factor]


def math_functions_used(code_lines) -> list[str]:
    """The math functions a kernel calls, sorted, for its `using std::...;` lines."""
    used = set()
    for line in code_lines:
        used.update(_FUNCTION_CALL.findall(line))
    return sorted(used)
