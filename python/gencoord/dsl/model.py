# SPDX-License-Identifier: BSD-3-Clause
"""The model-description API that `models/<name>.py` files use.

A model file builds one `Model`:

    model = Model(dim=2)
    theta = model.coordinate("theta", "angle from the downward vertical (rad)")
    l = model.parameter("l", 1.0, "rod length (m)")
    bob = model.particle("bob", mass=1, position=[l * sin(theta), -l * cos(theta)])
    model.gravity([0, -9.81])

Every declaration records the model-file line it came from, so later checks can point at it.
Nothing here derives anything: `derive/dense.py` does that from the recorded declarations.
"""

from __future__ import annotations

import math
from typing import Mapping, Sequence

import sympy as sp

from gencoord.errors import ModelError
from gencoord.dsl.bodies import add_point_masses, as_inertia
from gencoord.dsl.build_options import REQUESTED_OPTIONS, option_value
from gencoord.dsl.frames import Frame
from gencoord.dsl.joint_limits import JointLimits
from gencoord.dsl.kinematic_constraints import KinematicConstraints
from gencoord.dsl.speeds import GeneralizedSpeeds
from gencoord.dsl.items import (Body, BodyTorque, Coordinate, Damper, FixedPoint, GeneralizedForce,
                                Gravity, HolonomicConstraint, Input, Item, Parameter, Particle,
                                ParticleForce, Pin, Plane, Point, Rod, Speed, Spring,
                                VelocityConstraint, Wheel, as_point, as_scalar, as_vector,
                                caller_line, point_symbols)


class Model(GeneralizedSpeeds, KinematicConstraints, JointLimits):
    """A mechanical system described by particle positions x = X(q, t).

    `options` are the requested values of its build options (`option`), as text; by default
    those the loader requests for the model file it runs (requesting_options).
    """

    def __init__(self, dim: int, description: str | None = None, chart: str | None = None,
                 options: Mapping[str, str] | None = None):
        line = caller_line()
        if dim not in (2, 3):
            raise ModelError(f"dim must be 2 or 3, not {dim!r}", item="Model", line=line)
        self.dim = dim
        self.description = description
        self.line = line
        self.time = sp.Symbol("t", real=True)
        self.coordinates: list[Coordinate] = []
        # v in declaration order: ordinary coordinates (v = q') and free and ball joints'
        # speeds; rates[q] = q' in terms of v for the coordinates without a speed, and the
        # index in q of each unit quaternion's first entry (joints.py declares them)
        self._speed_order: list[Coordinate | Speed] = []
        self.rates: dict[sp.Symbol, sp.Expr] = {}
        self.quaternions: list[int] = []
        self.parameters: list[Parameter] = []
        self.particles: list[Particle] = []
        self.fixed_points: list[FixedPoint] = []
        self.gravities: list[Gravity] = []
        self.springs: list[Spring] = []
        self.dampers: list[Damper] = []
        self.particle_forces: list[ParticleForce] = []
        self.generalized_forces: list[GeneralizedForce] = []
        self.constraints: list[Rod | Pin | Plane] = []
        # constraints the coordinates do not remove (kinematic_constraints.py); wheels: pictures
        self.holonomic_constraints: list[HolonomicConstraint] = []
        self.velocity_constraints: list[VelocityConstraint] = []
        self.wheels: list[Wheel] = []
        self.limits: list = []  # joint_limits.py
        self.bodies: list[Body] = []
        self.torques: list[BodyTorque] = []
        # a joint tree's links (joints.py), parents first: the rigid-body recursions walk it
        self.links: list = []
        # the parameter s of its joints' friction -F tanh(qdot / s), once one has friction
        self.joint_friction_speed: sp.Symbol | None = None
        # what a loaded description (URDF) holds that the model leaves out, one line each
        self.ignored: list[str] = []
        self.options: dict[str, int | float | str] = {}
        self.requested_options = dict(REQUESTED_OPTIONS.get() if options is None else options)
        # an atlas: this model is the first chart; add_chart() appends the others
        self.chart = chart
        self.charts: list[Model] = []

    def _sympy_(self):
        # sympify() of the model (sin(model)) would fall back to parsing its repr
        raise ModelError("the model is not a number or an expression; use a symbol that "
                         "coordinate() or parameter() returns")  # the loader finds the line

    # --- options -------------------------------------------------------------------------
    def option(self, name: str, default, description: str, minimum=None, maximum=None):
        """A build option such as a chain's number of links; `generate --set name=value`.

        The generated model's name gets the value appended (`n_link_chain_5`), so every
        variant has its own header and C++ type. A requested value outside
        [minimum, maximum] (either bound optional) is refused with the range.
        """
        value = default
        if name in self.requested_options:
            value = option_value(name, self.requested_options[name], default, description,
                                 minimum, maximum)
        self.options[name] = value
        return value

    # --- an atlas of charts ----------------------------------------------------------------
    def add_chart(self, chart: "Model") -> None:
        """Adds another parameterization (chart) of the same particles, parameters and forces.

        The runtime (gencoord/atlas/atlas.hpp) switches to the best-conditioned chart when the
        current one nears a singular configuration. Both models must be named charts:
        `Model(dim=3, chart="pole_down")`. The generator checks that the particles, masses,
        parameters and forces agree.
        """
        line = caller_line()
        if not isinstance(chart, Model):
            raise ModelError("add_chart() takes another Model (the same system in other "
                             "coordinates)", item="add_chart", line=line)
        for model in (self, chart):
            if not model.chart:
                raise ModelError("every chart of an atlas needs a name: Model(dim=..., "
                                 "chart=\"name\")", item="add_chart", line=line)
        if chart is self or chart.charts:
            raise ModelError("add_chart() takes a plain chart (not this model, not an atlas)",
                             item=f"chart '{chart.chart}'", line=line)
        if chart.chart in [self.chart, *(c.chart for c in self.charts)]:
            raise ModelError(f"two charts are called '{chart.chart}'; give each its own name",
                             item=f"chart '{chart.chart}'", line=line)
        chart.line = line
        self.charts.append(chart)

    # --- coordinates, time and parameters ---------------------------------------------------
    def coordinate(self, name: str, description: str = "", initial: float = 0.0,
                   initial_rate: float = 0.0, *, has_speed: bool = True) -> sp.Symbol:
        """Declares a generalized coordinate; returns its symbol (use `rate(q)` for q-dot).

        `initial` and `initial_rate` suggest a starting state for demos and tools. A free or
        ball joint declares its coordinates without a speed (`has_speed=False`), then its
        speeds (`speed`) and their rates.
        """
        line = caller_line()
        try:
            initial, initial_rate = float(initial), float(initial_rate)
        except (TypeError, ValueError):
            raise ModelError("initial values must be numbers", item=f"coordinate '{name}'",
                             line=line)
        if not (math.isfinite(initial) and math.isfinite(initial_rate)):
            raise ModelError(f"initial values must be finite, not {initial} and {initial_rate}",
                             item=f"coordinate '{name}'", line=line)
        symbol = sp.Symbol(name, real=True)
        rate = sp.Symbol(f"{name}_dot", real=True)
        acceleration = sp.Symbol(f"{name}_ddot", real=True)
        self.coordinates.append(Coordinate(name, symbol, rate, acceleration, description, initial,
                                           initial_rate, has_speed, line=line))
        if has_speed:
            self._speed_order.append(self.coordinates[-1])
        return symbol

    def rate(self, coordinate: sp.Symbol) -> sp.Symbol:
        """The generalized velocity symbol of a coordinate, for generalized forces."""
        for c in self.coordinates:
            if c.symbol == coordinate and not c.has_speed:
                raise ModelError(f"{coordinate} belongs to a free or ball joint, whose rate is "
                                 "no speed of its own; write forces on that joint's link as "
                                 "body torques and point forces", item="rate()",
                                 line=caller_line())
            if c.symbol == coordinate:
                return c.rate
        raise ModelError(f"{coordinate} is not a declared coordinate", item="rate()",
                         line=caller_line())

    @property
    def t(self) -> sp.Symbol:
        return self.time

    def parameter(self, name: str, default: float, description: str) -> sp.Symbol:
        """Declares a parameter with its default value and a description with units."""
        line = caller_line()
        try:
            default = float(default)
        except (TypeError, ValueError):
            raise ModelError(f"default value {default!r} is not a number",
                             item=f"parameter '{name}'", line=line)
        if not math.isfinite(default):
            raise ModelError(f"default value {default!r} is not finite; give the value the "
                             "generated Params starts with", item=f"parameter '{name}'",
                             line=line)
        symbol = sp.Symbol(name, real=True)
        self.parameters.append(Parameter(name, symbol, default, description, line=line))
        return symbol

    def input(self, name: str, description: str) -> sp.Symbol:
        """Declares a control input u: a force the caller sets at run time (0 by default).

        Use the returned symbol in forces: on a coordinate (`generalized_force(s, u)`), at a
        point along a direction (`force(p, [u, 0])`), as a torque on a body (`torque(b, u)`).
        The generated Params holds its value like a parameter's; `input_matrix()` is
        B = dFt/du, so Mt qddot = Ft + Fi is B(q) u plus the rest when u enters linearly.
        """
        line = caller_line()
        symbol = sp.Symbol(name, real=True)
        self.parameters.append(Input(name, symbol, 0.0, description, line=line))
        return symbol

    # --- points --------------------------------------------------------------------------
    def particle(self, name: str, mass, position: Sequence) -> Particle:
        """A point mass at `position` = X(q, t), a SymPy vector of q, t and parameters.

        `particle.x` and `particle.xdot` are symbols for its position and velocity, to be
        used in user force expressions (`model.force`).
        """
        line = caller_line()
        label = f"particle '{name}'"
        x, xdot = point_symbols(name, self.dim)
        particle = Particle(name, as_vector(position, f"{label} position", self.dim, line),
                            x, xdot, as_scalar(mass, f"{label} mass", line), line=line)
        self.particles.append(particle)
        return particle

    def body(self, name: str, mass, inertia, frame: Frame) -> Body:
        """A rigid body of `mass` whose inertia tensor about its centre of mass, in body axes,
        is `inertia` (3x3, symmetric; a scalar in 2D), posed by `frame`: its rotation R(q, t)
        (a 3x3 matrix, or an angle in 2D) and its centre of mass p(q, t) as origin.

        Gravity acts at the centre of mass; `body.point(r)` gives points on the body for
        springs, dampers, rods, pins and forces; `model.torque(body, tau)` a torque.
        """
        line = caller_line()
        label = f"body '{name}'"
        if not isinstance(frame, Frame) or frame.dim != self.dim:
            raise ModelError(f"frame must be a {self.dim}D Frame(rotation, centre of mass), "
                             f"not {frame!r}", item=label, line=line)
        body = Body(name, as_scalar(mass, f"{label} mass", line),
                    as_inertia(inertia, self.dim, label, line), frame, line=line)
        add_point_masses(self, body)
        self.bodies.append(body)
        return body

    def torque(self, body: Body, torque, name: str | None = None) -> None:
        """A torque on a body: a world-frame vector (a scalar in 2D) that may use coordinates,
        `model.rate(q)`, t and parameters."""
        line = caller_line()
        name = name or f"on {getattr(body, 'name', body)}"
        label = f"torque '{name}'"
        if not isinstance(body, Body):
            given = body.label() if isinstance(body, Item) else repr(body)
            raise ModelError(f"acts on a body (what model.body() returns), not on {given}; "
                             "a force on a point is model.force()", item=label, line=line)
        value = (as_vector(torque, label, 3, line) if self.dim == 3
                 else sp.Matrix([as_scalar(torque, label, line)]))
        self.torques.append(BodyTorque(name, body, value, line=line))

    def fixed_point(self, name: str, position: Sequence) -> FixedPoint:
        """A massless anchor; its position may move with time (a prescribed pivot)."""
        line = caller_line()
        x, xdot = point_symbols(name, self.dim)
        point = FixedPoint(name, as_vector(position, f"fixed point '{name}' position",
                                           self.dim, line), x, xdot, line=line)
        self.fixed_points.append(point)
        return point

    # --- forces --------------------------------------------------------------------------
    def gravity(self, acceleration: Sequence) -> None:
        """Uniform gravity: force m_i g on every particle."""
        line = caller_line()
        self.gravities.append(Gravity(
            "gravity", as_vector(acceleration, "gravity", self.dim, line), line=line))

    def spring(self, a: Point, b: Point, stiffness, rest_length, damping=0,
               name: str | None = None) -> None:
        """A spring between two points in strain form (k is force per unit strain)."""
        line = caller_line()
        a, b = (as_point(point, "spring", line, Point) for point in (a, b))
        name = name or f"{a.name}-{b.name}"
        label = f"spring '{name}'"
        self.springs.append(Spring(
            name, a, b, as_scalar(stiffness, f"{label} stiffness", line),
            as_scalar(rest_length, f"{label} rest length", line),
            as_scalar(damping, f"{label} damping", line), line=line))

    def damper(self, a: Point, b: Point, coefficient, name: str | None = None) -> None:
        """A linear damper between two points; against a fixed point it is plain drag."""
        line = caller_line()
        a, b = (as_point(point, "damper", line, Point) for point in (a, b))
        name = name or f"{a.name}-{b.name}"
        self.dampers.append(Damper(name, a, b, as_scalar(
            coefficient, f"damper '{name}' coefficient", line), line=line))

    def force(self, particle: Particle, force: Sequence, potential=None,
              name: str | None = None) -> None:
        """A user force on a particle: expressions of points' `.x`, `.xdot`, t, parameters.

        Give `potential` (with -grad V = force) when the force is conservative, so that it
        enters the energy.
        """
        line = caller_line()
        particle = as_point(particle, "force", line, Particle)
        name = name or f"on {particle.name}"
        label = f"force '{name}'"
        self.particle_forces.append(ParticleForce(
            name, particle, as_vector(force, label, self.dim, line),
            None if potential is None else as_scalar(potential, f"{label} potential", line),
            line=line))

    def generalized_force(self, coordinate: sp.Symbol, force, potential=None,
                          name: str | None = None) -> None:
        """A force acting directly on a coordinate (a joint torque, a motor, a joint damper).

        `force` may use coordinates, `model.rate(q)`, t and parameters.
        """
        line = caller_line()
        target = self._coordinate_of(coordinate, "generalized_force", line)
        name = name or f"on {target.name}"
        label = f"generalized force '{name}'"
        self.generalized_forces.append(GeneralizedForce(
            name, target, as_scalar(force, label, line),
            None if potential is None else as_scalar(potential, f"{label} potential", line),
            line=line))

    def joint_spring(self, coordinate: sp.Symbol, stiffness, rest=0, damping=0,
                     name: str | None = None) -> None:
        """A linear spring (and damper) on a coordinate: -k (q - rest) - c q-dot."""
        line = caller_line()
        target = self._coordinate_of(coordinate, "joint_spring", line)
        name = name or f"joint spring on {target.name}"
        k = as_scalar(stiffness, f"joint spring '{name}' stiffness", line)
        rest = as_scalar(rest, f"joint spring '{name}' rest", line)
        c = as_scalar(damping, f"joint spring '{name}' damping", line)
        stretch = target.symbol - rest
        self.generalized_forces.append(GeneralizedForce(
            name, target, -k * stretch - c * target.rate, k * stretch**2 / 2, line=line))

    # --- declared constraints (verified and used by the maximal-coordinate model) ------------
    def rod(self, a: Point, b: Point, length, name: str | None = None) -> None:
        """A rigid rod: |x_b - x_a| = length must hold for every q and t."""
        line = caller_line()
        a, b = (as_point(point, "rod", line, Point) for point in (a, b))
        name = name or f"{a.name}-{b.name}"
        self.constraints.append(Rod(name, a, b, as_scalar(length, f"rod '{name}' length",
                                                          line), line=line))

    def pin(self, particle: Point, anchor, name: str | None = None) -> None:
        """A pin: the particle (or body point) sits at `anchor`: a position vector of t, a
        fixed point, or another moving point (two bodies joined at a point)."""
        line = caller_line()
        particle = as_point(particle, "pin", line, Point)
        name = name or f"{particle.name}"
        if isinstance(anchor, FixedPoint):
            anchor = anchor.position
        if not isinstance(anchor, Point):
            anchor = as_vector(anchor, f"pin '{name}' anchor", self.dim, line)
        self.constraints.append(Pin(name, particle, anchor, line=line))

    def plane(self, particle: Particle, normal: Sequence, offset=0,
              name: str | None = None) -> None:
        """A plane: normal . x = offset for the particle."""
        line = caller_line()
        particle = as_point(particle, "plane", line, Particle)
        name = name or f"{particle.name}"
        self.constraints.append(Plane(
            name, particle, as_vector(normal, f"plane '{name}' normal", self.dim, line),
            as_scalar(offset, f"plane '{name}' offset", line), line=line))

    # --- helpers -------------------------------------------------------------------------
    def _coordinate_of(self, symbol: sp.Symbol, where: str, line: int | None) -> Coordinate:
        for c in self.coordinates:
            if c.symbol == symbol and not c.has_speed:
                raise ModelError(f"{symbol} belongs to a free or ball joint, whose rate is no "
                                 "speed; act on its link with model.torque(...) and point "
                                 "forces", item=where, line=line)
            if c.symbol == symbol:
                return c
        raise ModelError(f"{symbol} is not a declared coordinate", item=where, line=line)

    @property
    def points(self) -> list[Point]:
        return [*self.particles, *self.fixed_points,
                *(point for body in self.bodies for point in body.points)]

    @property
    def inputs(self) -> list[Input]:
        """The control inputs, in declaration order (they are parameters too)."""
        return [p for p in self.parameters if isinstance(p, Input)]

    @property
    def nq(self) -> int:
        return len(self.coordinates)
