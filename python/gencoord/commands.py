# SPDX-License-Identifier: BSD-3-Clause
"""The entry points of the `gencoord` and `generate` commands (the scripts of a checkout, an
installation's bin/gencoord, pip's console scripts and `python -m gencoord`).

Each pins PYTHONHASHSEED before anything imports SymPy: SymPy's term order can depend on
string hashing, and generated code must be byte-identical from run to run.
"""

from __future__ import annotations

import importlib
import os
import sys


def _run(module: str, name: str) -> None:
    if os.environ.get("PYTHONHASHSEED") != "0":
        os.environ["PYTHONHASHSEED"] = "0"
        os.execv(sys.executable, [sys.executable, *sys.argv])
    try:
        status = importlib.import_module(module).main()
    except KeyboardInterrupt:  # during the imports (SymPy takes a second); main handles its own
        print(f"{name}: interrupted", file=sys.stderr)
        status = 130
    sys.exit(status)


def gencoord() -> None:
    """gencoord {generate,simulate,crosscheck,python,view,sweep,info} ..."""
    _run("gencoord.tool.main", "gencoord")


def generate() -> None:
    """generate MODEL.py [-o DIR] [--set key=value] ..."""
    _run("gencoord.generate.cli", "generate")
