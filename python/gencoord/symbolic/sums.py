# SPDX-License-Identifier: BSD-3-Clause
"""Sums of vectors' entries without SymPy's matrix arithmetic, for models of 1000 links.

- difference: a chain's positions are flat sums, each its parent's plus a few terms (a
  1000-link chain's last position has 2000 terms). SymPy subtracts two such sums by negating
  one and merging both, with assumption queries on every term; removing the shared terms
  directly costs a pass over them and gives the same canonical sum.
- dot and product: Matrix.dot and the matrix product convert both operands to a domain
  matrix first and test `0 * x` on every entry (assumption queries on each), milliseconds per
  call; the sum of the products is the same expression.
"""

from __future__ import annotations

from collections import Counter

import sympy as sp


def difference(x: sp.Matrix, base: sp.Matrix) -> sp.Matrix:
    """x - base, entry by entry; SymPy's subtraction where an entry of base has a term
    that x's entry lacks."""
    entries = []
    for xi, bi in zip(x, base):
        terms, removed = Counter(sp.Add.make_args(xi)), Counter(sp.Add.make_args(bi))
        if any(terms[term] < count for term, count in removed.items()):
            return x - base
        entries.append(sp.Add(*(terms - removed).elements()))
    return sp.Matrix(x.shape[0], x.shape[1], entries)


def dot(a: sp.Matrix, b: sp.Matrix) -> sp.Expr:
    """The dot product of two vectors of the same length."""
    return sp.Add(*[x * y for x, y in zip(a, b)])


def product(a: sp.Matrix, b: sp.Matrix) -> sp.Matrix:
    """The matrix product a b, each entry the sum of its nonzero products."""
    if a.shape[1] != b.shape[0]:
        raise sp.ShapeError(f"product of {a.shape} and {b.shape} matrices")
    zero = sp.S.Zero
    rows, columns = a.tolist(), b.T.tolist()
    entries = [sp.Add(*[x * y for x, y in zip(row, column) if x is not zero and y is not zero])
               for row in rows for column in columns]
    return sp.Matrix(a.shape[0], b.shape[1], entries)
