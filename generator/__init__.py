"""gencoord's generator: model file -> derivation -> one CSE -> C++ through Jinja2 templates.

Model files import what they need from here:

    from generator import Model, sin, cos
    from generator import Frame, rotation_z   # rigid bodies: poses and rotations
"""

__version__ = "0.1.0"

from sympy import Matrix, Rational, atan2, cos, exp, pi, sin, sqrt, tan  # noqa: E402,F401

from .errors import ModelError  # noqa: E402,F401
from .frames import (Frame, axis_angle, rotation_2d, rotation_about,  # noqa: E402,F401
                     rotation_x, rotation_y, rotation_z, rpy)
from .model import Model  # noqa: E402,F401

from .joints import Continuous, Fixed, Limits, Origin, Prismatic, Revolute  # noqa: E402,F401
from .joints import EULER_CHARTS, add_free_base, add_link  # noqa: E402,F401
from .urdf import load_urdf  # noqa: E402,F401
