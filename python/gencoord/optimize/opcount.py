# SPDX-License-Identifier: BSD-3-Clause
"""Operation counts for the generated code's comments (`Ops: N`).

`sympy.count_ops` spends about half a millisecond per expression telling subtraction from
negation and division from powers; the generator counts tens of thousands of intermediates.
This counts the expression tree instead: each Add or Mul of k arguments is k - 1 operations
(a -1 coefficient counts as one), each power or function call is one.
"""

from __future__ import annotations


from gencoord.derive.differentiate import ChainSum


def count_ops(expr) -> int:
    if isinstance(expr, ChainSum):  # factor * symbol terms: a product each, then the sum
        return len(expr.terms) - 1 + sum(count_ops(factor) + (symbol is not None and factor != 1)
                                         for factor, symbol in expr.terms)
    if expr.is_Atom:
        return 0
    args = expr.args
    inner = sum(count_ops(a) for a in args)
    if expr.is_Add or expr.is_Mul:
        return inner + len(args) - 1
    return inner + 1
