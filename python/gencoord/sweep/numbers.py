# SPDX-License-Identifier: BSD-3-Clause
"""Numbers in a sweep file: a TOML number, or a string of arithmetic on numbers and the
constants pi, tau and e ("-pi", "pi/2", "2*pi"), since TOML has no pi."""

from __future__ import annotations

import ast
import math
import operator
from typing import Callable

MAX_TEXT = 1000  # characters of arithmetic in one number: "pi/2" needs few
_CONSTANTS = {"pi": math.pi, "tau": math.tau, "e": math.e}
_BINARY = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
           ast.Div: operator.truediv, ast.Pow: operator.pow}
_UNARY: dict[type[ast.unaryop], Callable[[float], float]] = {
    ast.UAdd: operator.pos, ast.USub: operator.neg}


class NotANumber(ValueError):
    """The text is not arithmetic on numbers and pi, tau, e; the message says why."""


def as_float(value: int | float) -> float:
    """The number as a double; NotANumber for an integer no double holds."""
    try:
        return float(value)
    except OverflowError:
        raise NotANumber(f"{str(value)[:20]}... ({len(str(value))} digits) is too large for "
                         "a double") from None


def value_of(node: ast.AST) -> float:
    """The value of a parsed constant expression."""
    if isinstance(node, ast.Constant) and type(node.value) in (int, float):
        return as_float(node.value)
    if isinstance(node, ast.Name) and node.id in _CONSTANTS:
        return _CONSTANTS[node.id]
    if isinstance(node, ast.UnaryOp) and type(node.op) in _UNARY:
        return _UNARY[type(node.op)](value_of(node.operand))
    if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        try:
            result = _BINARY[type(node.op)](value_of(node.left), value_of(node.right))
        except (ZeroDivisionError, OverflowError) as error:
            raise NotANumber(f"{ast.unparse(node)}: {error}") from None
        if isinstance(result, complex):  # a negative number to a fractional power
            raise NotANumber(f"{ast.unparse(node)} is not a real number")
        return float(result)
    if isinstance(node, ast.Name):
        raise NotANumber(f"unknown name '{node.id}' (the constants are pi, tau and e)")
    raise NotANumber(f"'{ast.unparse(node)}' is not arithmetic on numbers and pi, tau, e")


def parse_number(value) -> float:
    """A finite float from a TOML value: an int, a float, or a string of arithmetic."""
    if isinstance(value, bool):
        raise NotANumber(f"expects a number, got {str(value).lower()}")
    if isinstance(value, (int, float)):
        result = as_float(value)
    elif isinstance(value, str):
        if len(value) > MAX_TEXT:
            raise NotANumber(f"a number of {len(value)} characters; write it in at most "
                             f"{MAX_TEXT}")
        try:
            tree = ast.parse(value.strip(), mode="eval")
            result = value_of(tree.body)
        except SyntaxError:
            raise NotANumber(f"'{value}' is not a number or arithmetic such as \"-pi/2\"") \
                from None
        except (RecursionError, MemoryError):  # parentheses nested thousands deep
            raise NotANumber("the arithmetic is nested too deeply; write the number out") \
                from None
    else:
        raise NotANumber(f"expects a number (or a string such as \"pi/2\"), got {value!r}")
    if not math.isfinite(result):
        raise NotANumber(f"expects a finite number, got {value!r}")
    return result
