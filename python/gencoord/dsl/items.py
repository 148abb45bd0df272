# SPDX-License-Identifier: BSD-3-Clause
"""What a model file declares, one dataclass per kind (coordinates, parameters, particles,
bodies, forces, constraints), each with the model-file line it came from.

`Model` (model.py) creates them; checks and derivations read them.
"""

from __future__ import annotations

import os
import sys
from dataclasses import dataclass, field
from typing import Iterable, Sequence, TypeVar

import sympy as sp

from gencoord.dsl.frames import Frame
from gencoord.errors import ModelError

# the gencoord package: frames in it are not the model file's
_PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__))) + os.sep


def model_file_frame():
    """The first stack frame outside this package: the model file's (None if there is none)."""
    # walks frames directly: inspect.stack() reads every frame's source lines, which cost
    # a tenth of the 20-link chain's generation time
    frame = sys._getframe(1)
    while frame is not None:
        if not os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE_DIR):
            return frame
        frame = frame.f_back
    return None


def caller_line() -> int | None:
    """The model file's line that made the current call."""
    frame = model_file_frame()
    return frame.f_lineno if frame is not None else None


@dataclass
class Item:
    """Anything declared in a model file: it has a kind, a name and a line."""
    name: str
    line: int | None = field(default=None, kw_only=True)

    kind = "item"

    def __post_init__(self):
        # every name reaches C++ identifiers and dictionaries: it must be text
        if not isinstance(self.name, str):
            raise ModelError(f"the name is {self.name!r}, not text; give a name such as "
                             f"\"{self.kind.split()[-1]}1\"", item=self.kind, line=self.line)

    def label(self) -> str:
        return f"{self.kind} '{self.name}'"

    def _sympy_(self):
        # sympify() of an item (sin(particle)) would fall back to parsing its repr
        raise ModelError("is not a number or an expression; use a symbol that "
                         "coordinate() or parameter() returns, or a point's .x or .xdot",
                         item=self.label())  # the loader finds the line in the traceback


@dataclass
class Coordinate(Item):
    symbol: sp.Symbol
    rate: sp.Symbol
    acceleration: sp.Symbol
    description: str
    initial: float = 0.0
    initial_rate: float = 0.0
    # False for a coordinate of a free or ball joint: its rate is G(q) v, not a speed
    has_speed: bool = True
    kind = "coordinate"


@dataclass
class Speed(Item):
    """A generalized speed: one entry of v. An ordinary coordinate's speed is its rate q'
    (the same symbol); a free or ball joint's are the components of its body's twist."""
    symbol: sp.Symbol
    acceleration: sp.Symbol
    description: str
    initial: float = 0.0
    kind = "speed"


@dataclass
class Parameter(Item):
    symbol: sp.Symbol
    default: float
    description: str
    kind = "parameter"


@dataclass
class Input(Parameter):
    """A control input: a parameter the caller changes while the model runs (0 unless set).

    It may appear only in forces, so the generalized force is Ft(q, v, t, u) and the input
    matrix B = dFt/du is what a linearization and a controller need."""
    kind = "input"


@dataclass
class Point(Item):
    """A point with a position: a particle (with mass) or a fixed/prescribed point."""
    position: sp.Matrix
    # Symbols standing for this point's position and velocity inside user force expressions.
    x: sp.Matrix
    xdot: sp.Matrix


@dataclass
class Particle(Point):
    mass: sp.Expr
    kind = "particle"


@dataclass
class BodyParticle(Particle):
    """One of the point masses that stand for a body (bodies.py): a particle the model file
    never names, labelled by its body."""
    body_name: str = ""

    def label(self) -> str:
        return f"body '{self.body_name}' (its point mass '{self.name}')"


@dataclass
class BodyPoint(Point):
    """A massless point fixed on a body at `offset` from its centre of mass (body axes).

    `weights` write it as an affine combination of the body's point masses, which is how the
    maximal-coordinate model, where the point masses move freely, places it and spreads the
    forces on it."""
    body: "Body"
    offset: sp.Matrix
    weights: list[sp.Expr]
    kind = "point"


@dataclass
class Body(Item):
    """A rigid body: mass, inertia tensor about the centre of mass in body axes (1x1 in 2D),
    and the frame (orientation R(q, t), centre of mass p(q, t)).

    The reduced dynamics take it whole (bodies.inertial_terms); `particles` are point masses
    with the body's mass, centre of mass and inertia tensor (bodies.py), which stand for it
    where positions are needed one by one (the particle kernels, the maximal model)."""
    mass: sp.Expr
    inertia: sp.Matrix
    frame: Frame
    particles: list[BodyParticle] = field(default_factory=list)
    second_moment: sp.Matrix | None = None  # S = integral of r r^T dm (bodies.py)
    offsets: list[sp.Matrix] = field(default_factory=list)  # the point masses', body axes
    points: list[BodyPoint] = field(default_factory=list)
    kind = "body"

    def affine_weights(self, offset: sp.Matrix) -> list[sp.Expr]:
        """Weights w_k with sum w_k = 1 and sum w_k r_k = offset: the point at `offset` as an
        affine combination of the point masses, w_k = 1/n + m_k r_k^T S^-1 offset (the r_k
        have mass-weighted mean zero and second moment S)."""
        count = len(self.offsets)
        inverse = self.second_moment_inverse()
        share = self.mass / count
        return [sp.Rational(1, count) + share * (r.T * inverse * offset)[0]
                for r in self.offsets]

    def second_moment_inverse(self) -> sp.Matrix:
        """S^-1, which places points by the point masses (affine_weights, and the maximal
        model's fit of the body's orientation)."""
        moment = self.second_moment
        assert moment is not None  # set with the point masses (bodies.add_point_masses)
        if moment.is_diagonal() or not moment.free_symbols:
            return moment.inv()
        # SymPy 1.11's inv() (elimination, simplifying as it goes) takes minutes on it
        return moment.adjugate() / moment.det()

    def point(self, offset: Sequence, name: str | None = None) -> BodyPoint:
        """The point fixed on this body at `offset` (body axes, from the centre of mass);
        springs, dampers, rods, pins and forces take it like a particle."""
        line = caller_line()
        name = name or f"{self.name}_point{len(self.points)}"
        r = as_vector(offset, f"point '{name}' of body '{self.name}'", self.frame.dim, line)
        x, xdot = point_symbols(name, self.frame.dim)
        point = BodyPoint(name, self.frame.point(r), x, xdot, self, r,
                          self.affine_weights(r), line=line)
        self.points.append(point)
        return point


@dataclass
class BodyTorque(Item):
    """A torque on a body: a world-frame vector (a scalar in 2D) of q, rates, t, parameters."""
    body: Body
    torque: sp.Matrix
    kind = "torque"


@dataclass
class FixedPoint(Point):
    """A massless point whose position may depend on parameters and time, never on q."""
    kind = "fixed point"


@dataclass
class Gravity(Item):
    acceleration: sp.Matrix
    kind = "gravity"


@dataclass
class Spring(Item):
    """A strain spring: f = k (|d| - L) / L along d, damping c ((v_b - v_a).d^) / L."""
    a: Point
    b: Point
    stiffness: sp.Expr
    rest_length: sp.Expr
    damping: sp.Expr
    kind = "spring"


@dataclass
class Damper(Item):
    """A linear damper: force c (v_b - v_a) on b and the opposite on a."""
    a: Point
    b: Point
    coefficient: sp.Expr
    kind = "damper"


@dataclass
class ParticleForce(Item):
    """A user force on a particle or a body point, a SymPy expression of point x/xdot symbols,
    t and parameters."""
    particle: Point
    force: sp.Matrix
    potential: sp.Expr | None
    kind = "force"


@dataclass
class GeneralizedForce(Item):
    """A force acting directly on one coordinate (joint torque, joint spring)."""
    coordinate: Coordinate
    force: sp.Expr
    potential: sp.Expr | None
    kind = "generalized force"


@dataclass
class Rod(Item):
    a: Point
    b: Point
    length: sp.Expr
    kind = "rod"


@dataclass
class Pin(Item):
    """The point sits at the anchor: a position vector of t and parameters, or another point
    (a joint between two bodies)."""
    particle: Point
    anchor: sp.Matrix | Point
    # the joint whose two halves it holds: true by the joint's kinematics, so not checked
    joint: str | None = field(default=None, kw_only=True)
    kind = "pin"


@dataclass
class Plane(Item):
    particle: Particle
    normal: sp.Matrix
    offset: sp.Expr
    kind = "plane"


@dataclass
class HolonomicConstraint(Item):
    """C(q, t) = 0 where the coordinates do not satisfy it by construction (a closed loop):
    one scalar row, an expression of q, t, parameters and points' `.x`."""
    expr: sp.Expr
    wheel: str = field(default="", kw_only=True)  # the rolling wheel it belongs to, if any
    kind = "holonomic constraint"


@dataclass
class VelocityConstraint(Item):
    """A(q, t) v + b(q, t) = 0 (rolling without slipping): one scalar row, linear in the
    speeds, an expression of q, the speeds, t, parameters and points' `.x` and `.xdot`."""
    expr: sp.Expr
    wheel: str = field(default="", kw_only=True)  # the rolling wheel it belongs to, if any
    kind = "velocity constraint"


@dataclass
class Wheel(Item):
    """A wheel of `rolling_wheel`, kept for pictures: its body, radius, and axle and centre in
    the body's axes (the dynamics have its velocity constraints)."""
    body: Body
    radius: sp.Expr
    axle: sp.Matrix
    center: sp.Matrix
    kind = "wheel"


def as_vector(values: Iterable, what: str, dim: int, line: int | None) -> sp.Matrix:
    try:
        is_sequence = not isinstance(values, (str, bytes)) and iter(values) is not None
    except TypeError:
        is_sequence = False
    if not is_sequence:
        raise ModelError(f"is {values!r}, not a vector; give a list of {dim} numbers or "
                         "expressions", item=what, line=line)
    entries = list(values)
    if len(entries) != dim:
        raise ModelError(
            f"has {len(entries)} components but the model is {dim}-dimensional; give "
            f"exactly {dim}", item=what, line=line)
    return sp.Matrix([as_scalar(value, f"{what}[{k}]", line) for k, value in enumerate(entries)])


def as_scalar(value, what: str, line: int | None) -> sp.Expr:
    """`value` as a finite SymPy expression, or a ModelError naming `what`: text, None,
    booleans, containers, NaN and infinities are refused (the imaginary unit later, by the
    checks of every expression)."""
    if isinstance(value, (str, bytes)):
        raise ModelError(f"is the text {value!r}, not an expression; use numbers and the "
                         "symbols that coordinate(), parameter() and input() return",
                         item=what, line=line)
    if value is None or isinstance(value, bool):
        raise ModelError(f"is {value!r}, not a number or an expression", item=what, line=line)
    if isinstance(value, Item):
        raise ModelError(f"is {value.label()}, not a number or an expression", item=what,
                         line=line)
    try:
        expr = sp.sympify(value, strict=True)
    except (TypeError, ValueError, sp.SympifyError):
        raise ModelError(f"is a {type(value).__name__}, not a number or an expression",
                         item=what, line=line) from None
    if not isinstance(expr, sp.Expr):
        raise ModelError(f"is a {type(value).__name__}, not a scalar expression", item=what,
                         line=line)
    if expr.has(sp.AccumBounds):
        raise ModelError(f"is {expr}: a function of an infinite number (such as cos(1e400)); "
                         "give finite numbers", item=what, line=line)
    if expr.has(sp.nan, sp.oo, -sp.oo, sp.zoo):
        raise ModelError(f"is {expr} (not finite); give a finite number or expression",
                         item=what, line=line)
    return expr


PointKind = TypeVar("PointKind", bound="Point")


def as_point(value, what: str, line: int | None, kind: type[PointKind]) -> PointKind:
    """`value` if it is a `kind` of point (Point: a particle, a fixed point, a body's point;
    Particle: one with mass), else a ModelError naming `what`."""
    if not isinstance(value, kind):
        given = value.label() if isinstance(value, Item) else f"{value!r}"
        wanted = ("points (what particle(), fixed_point() or body.point() return)"
                  if kind is Point else "a particle or a body's point")
        raise ModelError(f"acts on {wanted}, not {given}", item=what, line=line)
    return value


def point_symbols(name: str, dim: int) -> tuple[sp.Matrix, sp.Matrix]:
    """The symbols standing for a point's position and velocity in force expressions."""
    axes = "xyz"[:dim]
    x = sp.Matrix([sp.Symbol(f"{name}.{a}", real=True) for a in axes])
    xdot = sp.Matrix([sp.Symbol(f"{name}.{a}dot", real=True) for a in axes])
    return x, xdot
