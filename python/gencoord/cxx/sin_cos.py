# SPDX-License-Identifier: BSD-3-Clause
"""Sines and cosines of a kernel's coordinates, all in one call.

Straight-line code takes `sin` and `cos` of most coordinates of a tree of revolute joints,
one libm call per argument, a sizeable share of a small kernel (docs/performance.md,
section 6). A kernel or part that takes them of two or more coordinates gets them
instead from one call of the header's `gencoord_kernel_math::sin_cos` at its start, which
evaluates them for double in vector registers through glibc's vector math library
(sin_cos.j2). The code's `sin(name)` and `cos(name)` of those coordinates become `sin_of[i]`
and `cos_of[i]`.
"""

from __future__ import annotations

import re

# the locals the batch declares (reserved_names.py keeps them from model names)
SIN_COS_LOCALS = ("sin_cos_of", "sin_of", "cos_of")
# fewer arguments gain nothing from a vector call
MIN_ARGUMENTS = 2

_CALL = re.compile(r"(?<![\w.:])(sin|cos)\(([A-Za-z_]\w*)\)")


def batch_sin_cos(coordinates: list[str], codes: list[str]) -> tuple[list[str], list[str]]:
    """(the coordinates batched, in the order of `coordinates`; `codes` reading the batch).

    `coordinates` are the local names of the coordinates the code reads; only sines and
    cosines of those names themselves are batched. Fewer than MIN_ARGUMENTS leave the
    code as it is."""
    called = {match.group(2) for code in codes for match in _CALL.finditer(code)}
    arguments = [name for name in coordinates if name in called]
    if len(arguments) < MIN_ARGUMENTS:
        return [], codes
    index = {name: i for i, name in enumerate(arguments)}

    def read(match: re.Match) -> str:
        function, name = match.groups()
        return f"{function}_of[{index[name]}]" if name in index else match.group(0)
    return arguments, [_CALL.sub(read, code) for code in codes]
