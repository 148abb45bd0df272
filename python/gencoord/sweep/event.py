# SPDX-License-Identifier: BSD-3-Clause
"""The event of a sweep: a condition on the state, `abs(theta1) > pi or abs(theta2) > pi`,
checked at every step; the first time it holds is the sample's event time.

A condition is one comparison or several joined by `or`. A comparison sets a quantity against
a constant: a coordinate (`theta1`), its velocity (`theta1_dot`) or the total `energy`,
optionally inside `abs()`, compared with `>`, `>=`, `<` or `<=` to arithmetic on numbers and
pi, tau, e (either side may hold the quantity)."""

from __future__ import annotations

import ast
from dataclasses import dataclass

from gencoord.sweep.numbers import NotANumber, value_of

_OPERATORS = {ast.Gt: ">", ast.GtE: ">=", ast.Lt: "<", ast.LtE: "<="}
_MIRRORED = {">": "<", ">=": "<=", "<": ">", "<=": ">="}


class EventSyntaxError(ValueError):
    """The condition cannot be read; the message says why."""


@dataclass(frozen=True)
class Clause:
    """`[abs(]name[)] op value`; `kind` is q, v or energy once resolved against the model."""
    name: str
    absolute: bool
    op: str
    value: float
    kind: str = ""
    coordinate: str = ""

    def text(self) -> str:
        quantity = f"abs({self.name})" if self.absolute else self.name
        return f"{quantity} {self.op} {self.value!r}"


def _quantity(node: ast.AST) -> tuple[str, bool] | None:
    """(name, absolute) if `node` is a name or abs(name), else None."""
    if isinstance(node, ast.Name):
        return node.id, False
    if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
            and node.func.id == "abs" and len(node.args) == 1 and not node.keywords
            and isinstance(node.args[0], ast.Name)):
        return node.args[0].id, True
    return None


def _clause(node: ast.AST) -> Clause:
    if not isinstance(node, ast.Compare) or len(node.ops) != 1:
        raise EventSyntaxError(f"'{ast.unparse(node)}' is not one comparison such as "
                               "abs(theta1) > pi")
    op = _OPERATORS.get(type(node.ops[0]))
    if op is None:
        raise EventSyntaxError(f"'{ast.unparse(node)}': compare with >, >=, < or <=")
    left, right = node.left, node.comparators[0]
    quantity = _quantity(left)
    constant = right
    if quantity is None or (isinstance(left, ast.Name) and left.id in ("pi", "tau", "e")):
        quantity, constant, op = _quantity(right), left, _MIRRORED[op]
    if quantity is None:
        raise EventSyntaxError(f"'{ast.unparse(node)}': one side must be a coordinate, a "
                               "velocity (name_dot) or energy, or abs() of one")
    try:
        value = value_of(constant)
    except NotANumber as error:
        raise EventSyntaxError(f"'{ast.unparse(node)}': {error}") from None
    return Clause(name=quantity[0], absolute=quantity[1], op=op, value=value)


def parse_condition(text: str) -> tuple[Clause, ...]:
    """The clauses of `text` (any of them holding makes the event happen)."""
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError:
        raise EventSyntaxError(f"'{text}' cannot be read; write e.g. "
                               "\"abs(theta1) > pi or theta2_dot < -10\"") from None
    body = tree.body
    if isinstance(body, ast.BoolOp):
        if not isinstance(body.op, ast.Or):
            raise EventSyntaxError("only 'or' joins comparisons; an event happens when any of "
                                   "them holds")
        return tuple(_clause(value) for value in body.values)
    return (_clause(body),)


def velocity_names(coordinates: list[str], speeds: list[str] | None = None) -> dict[str, str]:
    """What an event calls each entry of v, mapped to the entry's name: `<coordinate>_dot`
    where the speed is a coordinate's rate, a free or ball joint's speed by its own name
    (`trunk_wz`); `speeds` the names of v's entries (None: the coordinates, v = q')."""
    return {(s + "_dot" if s in coordinates else s): s
            for s in (coordinates if speeds is None else speeds)}


def resolve(clause: Clause, coordinates: list[str], velocities: dict[str, str]) -> Clause:
    """The clause with its quantity's kind: a coordinate (q), a velocity (v, `velocities` as
    velocity_names() gives them) or energy.
    \\throws EventSyntaxError naming what the model has, for another name."""
    if clause.name in coordinates:
        kind, coordinate = "q", clause.name
    elif clause.name in velocities:
        kind, coordinate = "v", velocities[clause.name]
    elif clause.name == "energy":
        kind, coordinate = "energy", ""
    else:
        raise EventSyntaxError(
            f"'{clause.name}' is not a coordinate, a velocity or energy of the model (it has "
            f"{', '.join(coordinates)}; velocities {', '.join(velocities)}; and energy)")
    return Clause(clause.name, clause.absolute, clause.op, clause.value, kind, coordinate)
