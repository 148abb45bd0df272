# SPDX-License-Identifier: BSD-3-Clause
"""Numeric evaluation of user expressions that may leave their domain.

Positions such as sqrt(1 - s^2), 1 / s or tan(q) have no real value at some sampled
configurations: math raises ValueError (sqrt of a negative), ZeroDivisionError, or lambdify
returns a complex number. The sampled checks evaluate where the values are finite and count
the rest, instead of failing with a traceback.
"""

from __future__ import annotations

import math


def _all_finite(values) -> bool:
    for value in values:
        if isinstance(value, (list, tuple)):
            if not _all_finite(value):
                return False
        elif not (isinstance(value, (int, float)) and math.isfinite(value)):
            return False
    return True


def finite_or_none(function, *arguments):
    """function(*arguments) when it evaluates to real, finite numbers (a number or nested
    lists of them), else None."""
    try:
        values = function(*arguments)
    except (ArithmeticError, ValueError, TypeError):
        return None
    if isinstance(values, (list, tuple)):
        return values if _all_finite(values) else None
    return values if _all_finite([values]) else None
