# SPDX-License-Identifier: BSD-3-Clause
"""The generator's former package name, kept so that model files written for it still run.

`from generator import Model` (and `from generator.urdf import load_urdf`) give the same
objects as `from gencoord import ...`, and print once which line to change.
"""

from __future__ import annotations

import os
import sys

_TOLD: set[str] = set()


def tell_to_rename(old: str, new: str) -> None:
    """Print `file:line: warning: ...` for the import of `old` in the model file, once."""
    frame = sys._getframe(1)
    here = os.path.dirname(os.path.abspath(__file__)) + os.sep
    while frame is not None and (frame.f_code.co_filename.startswith("<")
                                 or os.path.abspath(frame.f_code.co_filename).startswith(here)):
        frame = frame.f_back
    where = f"{frame.f_code.co_filename}:{frame.f_lineno}" if frame is not None else "gencoord"
    if where in _TOLD:
        return
    _TOLD.add(where)
    print(f"{where}: warning: the package `{old}` is now `{new}`: write `from {new} import ...`",
          file=sys.stderr)


tell_to_rename("generator", "gencoord")

from gencoord import *  # noqa: E402,F401,F403
from gencoord import __all__, __version__  # noqa: E402,F401
