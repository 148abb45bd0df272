# SPDX-License-Identifier: BSD-3-Clause
"""Differences between the SymPy and Jinja2 versions the generator supports, in one place.

Supported: SymPy 1.11 to 1.14, Jinja2 3.0 and later. Each switch says why it exists.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

import jinja2

if TYPE_CHECKING:
    from sympy.printing.codeprinter import CodePrinter


def version_tuple(version: str) -> tuple[int, ...]:
    """The leading numeric fields of a version string: '3.1.2' -> (3, 1, 2), '1.14.0rc1' ->
    (1, 14, 0), 'dev' -> ()."""
    numbers = []
    for field in version.split("."):
        match = re.match(r"\d+", field)
        if match is None:
            break
        numbers.append(int(match.group()))
        if match.end() != len(field):
            break
    return tuple(numbers)


def code_printer_settings(printer_class: type[CodePrinter], **settings) -> dict:
    """`settings`, less 'strict' where `printer_class` does not know it.

    SymPy 1.13 added the code printers' 'strict' setting (raise on an expression they cannot
    print); older printers reject any unknown setting. Dropping it there changes nothing for
    a printer that raises from _print_not_supported itself, as ours does."""
    known = printer_class._default_settings
    return {key: value for key, value in settings.items() if key != "strict" or key in known}


# Jinja2 3.1.2 and later write a cache entry to a temporary file and rename it, so a parallel
# generator (make -j) never reads half of one; older versions write in place and fail on an
# entry cut short while another process writes it, so they get no cache.
JINJA2_CACHE_IS_SAFE = version_tuple(jinja2.__version__) >= (3, 1, 2)
