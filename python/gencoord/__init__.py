# SPDX-License-Identifier: BSD-3-Clause
"""gencoord: generalized-coordinate dynamics, from a model file to fast C++.

Model files import what they need from here:

    from gencoord import Model, sin, cos
    from gencoord import Frame, rotation_z   # rigid bodies: poses and rotations
    from gencoord.urdf import load_urdf       # a robot description as a joint tree

The generator runs as stages, each a sub-package: dsl/ (the model-file API), urdf/,
checks/, derive/, optimize/ and cxx/ (the C++ backend and its templates), driven by
generate/. tool/ is the `gencoord` command, sweep/ its ensembles, viewer/ its pages.

The names below load on first use, so that `import gencoord` (and the `gencoord` command,
which does not always need it) does not import SymPy.
"""

from __future__ import annotations

import importlib

__version__ = "0.1.0"

# public name -> the module that defines it
_API = {
    **{name: "sympy" for name in ("Matrix", "Rational", "atan2", "cos", "exp", "pi", "sin",
                                  "sqrt", "tan")},
    "ModelError": "gencoord.errors",
    **{name: "gencoord.dsl.frames" for name in ("Frame", "axis_angle", "rotation_2d",
                                                "rotation_about", "rotation_x", "rotation_y",
                                                "rotation_z", "rpy")},
    "Model": "gencoord.dsl.model",
    **{name: "gencoord.dsl.joints" for name in ("Ball", "Continuous", "Fixed", "Free", "Limits",
                                                "Mimic", "Origin", "Prismatic", "Revolute",
                                                "EULER_CHARTS", "add_free_base", "add_link")},
    "load_urdf": "gencoord.urdf.load",
}

__all__ = sorted(_API)


def __getattr__(name: str):
    module = _API.get(name)
    if module is None:
        raise AttributeError(f"module 'gencoord' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_API))
