# SPDX-License-Identifier: BSD-3-Clause
"""Checks a loaded model before anything is derived; each failure names the item and line."""

from __future__ import annotations

import sympy as sp
from sympy.core.function import AppliedUndef

from gencoord.checks.rotations import rotation_problem
from gencoord.errors import ModelError
from gencoord.symbolic.emittable import expression_problem
from gencoord.dsl.bodies import inertia_problem
from gencoord.dsl.model import Model
from gencoord.dsl.items import Body, Damper, Pin, Point, Rod, Spring
from gencoord.cxx.reserved_names import name_problem


def _check_name(name: str, label: str, line: int | None) -> None:
    problem = name_problem(name)
    if problem:
        raise ModelError(problem, item=label, line=line)


def _check_names(model: Model) -> None:
    seen: dict[str, str] = {}
    symbols = [*model.coordinates, *model.joint_speeds, *model.parameters]
    body_points = [point for body in model.bodies for point in body.points]
    for item in [*symbols, *model.bodies, *model.particles, *model.fixed_points, *body_points]:
        _check_name(item.name, item.label(), item.line)
        if item.name in seen:
            raise ModelError(f"the name '{item.name}' is already used by {seen[item.name]}; "
                             "give each item its own name", item=item.label(), line=item.line)
        seen[item.name] = item.label()
    for c in model.coordinates:
        for derived in (c.rate.name, c.acceleration.name):
            problem = name_problem(derived)
            if problem:
                raise ModelError(f"its velocity or acceleration is called {derived}: {problem}",
                                 item=c.label(), line=c.line)
            if derived in seen:
                raise ModelError(f"'{derived}' is a derivative of {c.label()}; rename the "
                                 "other item", item=seen[derived], line=c.line)


def _check_expression(expr, allowed: set, label: str, line: int | None, hint: str, *,
                      constants: set, velocities: dict,
                      inputs: set | frozenset = frozenset()) -> None:
    """`expr` uses only `allowed` symbols and what emittable.py accepts; `constants` are the
    parameters, `velocities` maps each coordinate's rate and acceleration to it, `inputs`
    are the control inputs (allowed in forces only)."""
    expr = sp.sympify(expr)
    functions = sorted(str(f) for f in expr.atoms(AppliedUndef))
    if functions:
        raise ModelError(f"uses {', '.join(functions)}: a function SymPy cannot evaluate; "
                         "write it with elementary functions (sin, exp, sqrt ...)",
                         item=label, line=line)
    problem = expression_problem(expr, constants)
    if problem:
        raise ModelError(problem, item=label, line=line)
    unknown = expr.free_symbols - allowed
    if not unknown:
        return
    names = sorted(str(s) for s in unknown)
    moving = sorted(f"{s} = model.rate({velocities[s].name})" for s in unknown
                    if s in velocities)
    if moving:
        raise ModelError(f"may not depend on velocities, but uses {', '.join(moving)}; {hint}",
                         item=label, line=line)
    misplaced_inputs = sorted(str(s) for s in unknown & inputs)
    if misplaced_inputs:
        raise ModelError(f"uses the input {', '.join(misplaced_inputs)}; an input acts only "
                         "through forces (model.force, model.generalized_force, model.torque, "
                         "springs and dampers), not in positions, masses, constraints or "
                         "potentials", item=label, line=line)
    allowed_names = {str(a) for a in allowed}
    lookalikes = sorted(name for name in names if name in allowed_names)
    if lookalikes:
        raise ModelError(f"uses a symbol {', '.join(lookalikes)} made outside the model, not the "
                         "one the model declared under that name; use the symbol that "
                         "model.parameter() or model.coordinate() returned", item=label, line=line)
    raise ModelError(f"uses {', '.join(names)}, which {'is' if len(names) == 1 else 'are'}"
                     f" not declared; {hint}", item=label, line=line)


class _Symbols:
    """The symbol sets a model's expressions may use, and the check of one expression."""

    def __init__(self, model: Model):
        # forces may use every parameter; kinematics, masses and potentials not the inputs
        self.forcing = {p.symbol for p in model.parameters}
        self.inputs = {p.symbol for p in model.inputs}
        self.params = self.forcing - self.inputs
        self.q = {c.symbol for c in model.coordinates}
        self.rates = {speed.symbol for speed in model.speeds}
        self.t = {model.time}
        self.points = {s for point in model.points for s in (*point.x, *point.xdot)}
        self.velocities = {s: c for c in model.coordinates for s in (c.rate, c.acceleration)}

    def check(self, expr, allowed, label, line, hint) -> None:
        _check_expression(expr, allowed, label, line, hint, constants=self.forcing,
                          velocities=self.velocities, inputs=self.inputs)


_DECLARE = "declare it with model.parameter() or model.coordinate()"


def _check_expressions(model: Model, defaults: dict) -> None:
    symbols = _Symbols(model)
    kinematic = symbols.q | symbols.t | symbols.params
    composed = {id(link.body) for link in model.links}  # joints.py's frames are rotations
    for body in model.bodies:
        _check_body(body, defaults, symbols.check, kinematic, symbols.params)
        if id(body) not in composed:
            variables = [*(c.symbol for c in model.coordinates), model.time]
            problem = rotation_problem(body.frame.rotation, variables, defaults)
            if problem:
                raise ModelError(problem, item=body.label(), line=body.line)
    for torque in model.torques:
        symbols.check(torque.torque, symbols.q | symbols.rates | symbols.t | symbols.forcing,
                      torque.label(), torque.line,
                      "a torque may use coordinates, model.rate(q), t and parameters")
    _check_particles(model, symbols, defaults)
    for point in model.fixed_points:
        symbols.check(point.position, symbols.t | symbols.params, f"{point.label()} position",
                      point.line, "a fixed point may depend only on parameters and t")
    _check_forces(model, symbols)
    _check_constraint_terms(model, symbols)
    _check_kinematic_constraint_terms(model, symbols)


def _check_particles(model: Model, symbols: _Symbols, defaults: dict) -> None:
    q, t, params = symbols.q, symbols.t, symbols.params
    accepted_terms: set = set()  # a chain's position repeats its parent's terms: check each once
    for particle in model.particles:
        entries = [sp.Add.make_args(entry) for entry in particle.position]
        symbols.check(sp.Matrix([sp.Add(*[term for term in terms if term not in accepted_terms])
                                 for terms in entries]),
                      q | t | params, f"{particle.label()} position",
                      particle.line, "positions X(q, t) are functions of the coordinates, "
                      "t and parameters; declare any other symbol with model.parameter()")
        accepted_terms.update(term for terms in entries for term in terms)
        symbols.check(particle.mass, q | t | params, f"{particle.label()} mass",
                      particle.line, _DECLARE)
        depends = sorted(str(s) for s in particle.mass.free_symbols & (q | t))
        if depends:
            raise ModelError(f"mass depends on {', '.join(depends)}; a particle's mass must be "
                             "a constant or a parameter", item=particle.label(), line=particle.line)
        _check_positive_mass(particle, defaults)


def _check_forces(model: Model, symbols: _Symbols) -> None:
    q, rates, t = symbols.q, symbols.rates, symbols.t
    forcing, params, check = symbols.forcing, symbols.params, symbols.check
    for item in model.gravities:
        check(item.acceleration, t | forcing, item.label(), item.line, _DECLARE)
    for spring in model.springs:
        for what, expr in (("stiffness", spring.stiffness), ("rest length", spring.rest_length),
                           ("damping", spring.damping)):
            check(expr, t | (forcing if what == "damping" else params),
                  f"{spring.label()} {what}", spring.line,
                  "spring constants may depend only on parameters and t")
    for damper in model.dampers:
        check(damper.coefficient, t | forcing, damper.label(), damper.line, _DECLARE)
    for force in model.particle_forces:
        check(force.force, symbols.points | t | forcing, force.label(), force.line,
              "a particle force may use points' .x and .xdot, t and parameters")
        if force.potential is not None:
            check(force.potential, symbols.points | t | params, force.label(),
                  force.line, "a potential may use points' .x, t and parameters")
    for generalized in model.generalized_forces:
        if not generalized.coordinate.has_speed:
            raise ModelError(f"acts on {generalized.coordinate.name}, a coordinate of a free or "
                             "ball joint, whose rate is no speed; act on its link with "
                             "model.torque(...) and point forces", item=generalized.label(),
                             line=generalized.line)
        check(generalized.force, q | rates | t | forcing, generalized.label(), generalized.line,
              "a generalized force may use coordinates, model.rate(q), t, parameters")
        if generalized.potential is not None:
            check(generalized.potential, q | t | params, f"{generalized.label()} potential",
                  generalized.line, "a potential may use coordinates, t and parameters")


def _check_constraint_terms(model: Model, symbols: _Symbols) -> None:
    """Rod lengths, pin anchors and plane normals and offsets: parameters and t only."""
    for constraint in model.constraints:
        if isinstance(constraint, Rod):
            parts = [("length", constraint.length)]
        elif isinstance(constraint, Pin):
            parts = [] if isinstance(constraint.anchor, Point) else [("anchor", constraint.anchor)]
        else:
            parts = [("normal", constraint.normal), ("offset", constraint.offset)]
        for what, expr in parts:
            symbols.check(expr, symbols.t | symbols.params, f"{constraint.label()} {what}",
                          constraint.line, "a constraint may depend only on parameters and t")


def _check_kinematic_constraint_terms(model: Model, symbols: _Symbols) -> None:
    """Holonomic constraints: q, t, parameters, points' .x; velocity constraints also the
    speeds and points' .xdot. Each row's name once."""
    positions = {s for point in model.points for s in point.x}
    seen: set[str] = set()
    for item in model.holonomic_constraints:
        symbols.check(item.expr, symbols.q | symbols.t | symbols.params | positions,
                      item.label(), item.line, "a holonomic constraint may use coordinates, "
                      "t, parameters and points' .x")
    for row in model.velocity_constraints:
        symbols.check(row.expr, symbols.q | symbols.rates | symbols.t | symbols.params
                      | symbols.points, row.label(), row.line, "a velocity constraint may "
                      "use coordinates, speeds (model.rate(q)), t, parameters and points' .x "
                      "and .xdot")
    for constraint in [*model.holonomic_constraints, *model.velocity_constraints]:
        if constraint.name in seen:
            raise ModelError(f"the name '{constraint.name}' is already used by another "
                             "constraint; give each constraint its own name",
                             item=constraint.label(), line=constraint.line)
        seen.add(constraint.name)


def _check_body(body: Body, defaults: dict, check_symbols, kinematic: set, params: set) -> None:
    """A body's frame may use q, t and parameters; its mass and inertia only parameters, and
    with the default parameters they must be a possible rigid body's."""
    label = body.label()
    check_symbols(body.frame.rotation, kinematic, f"{label} rotation", body.line,
                  "a body's rotation R(q, t) is a function of the coordinates, t and parameters")
    check_symbols(body.frame.origin, kinematic, f"{label} centre of mass", body.line,
                  "a body's centre of mass p(q, t) is a function of the coordinates, t and "
                  "parameters")
    for what, expr in (("mass", body.mass), ("inertia", body.inertia)):
        moving = sorted(str(s) for s in sp.sympify(expr).free_symbols & (kinematic - params))
        if moving:
            raise ModelError(f"{what} depends on {', '.join(moving)}; a body's mass and inertia "
                             "must be constants or parameters", item=label, line=body.line)
        check_symbols(expr, params, f"{label} {what}", body.line,
                      "a body's mass and inertia are constants or parameters")
    problem = inertia_problem(body.mass.xreplace(defaults), body.inertia.xreplace(defaults))
    if problem:
        raise ModelError(f"{problem} (with the default parameters)", item=label, line=body.line)


def _default_values(model: Model) -> dict:
    """Each parameter's symbol -> its default value, for xreplace (not subs: subs tries every
    parameter of a 100-link chain on every mass)."""
    return {p.symbol: sp.sympify(p.default) for p in model.parameters}


def _check_positive_mass(particle, defaults: dict) -> None:
    value = particle.mass.xreplace(defaults)
    if not (value.is_number and value.is_extended_positive and value.is_finite):
        raise ModelError(f"mass is {particle.mass} = {value} with the default parameters; "
                         "a particle's mass must be positive", item=particle.label(),
                         line=particle.line)


def _check_descriptions(model: Model) -> None:
    """Descriptions are printed into one-line C++ comments (`/// ...`): one line of text,
    not ending in a backslash, which would continue the comment onto the next line."""
    described = [(c.label(), c.description, c.line) for c in model.coordinates]
    described += [(p.label(), p.description, p.line) for p in model.parameters]
    for label, text, line in described:
        if not isinstance(text, str):
            raise ModelError(f"description is {text!r}, not text; give a string",
                             item=label, line=line)
        if any(ord(character) < 32 for character in text):
            raise ModelError("description has a line break or another control character; "
                             "write it on one line", item=label, line=line)
        if text.rstrip().endswith("\\"):
            raise ModelError("description ends in a backslash, which would continue the C++ "
                             "comment it is printed in; remove it", item=label, line=line)


def _check_connections(model: Model) -> None:
    """A spring, damper or rod joins two different points."""
    joined: list[Spring | Damper | Rod] = [*model.springs, *model.dampers]
    joined += [c for c in model.constraints if isinstance(c, Rod)]
    for item in joined:
        if item.a is item.b:
            raise ModelError(f"connects {item.a.label()} to itself; give two different points",
                             item=item.label(), line=item.line)


def _check_rest_lengths(model: Model, defaults: dict) -> None:
    """The strain spring divides by its rest length: it must be positive (when it is a
    number with the default parameters; one that varies with t is the model's to keep so)."""
    for spring in model.springs:
        value = spring.rest_length.xreplace(defaults)
        if value.is_number and not (value.is_extended_positive and value.is_finite):
            shown = (f"{value}" if value == spring.rest_length else
                     f"{spring.rest_length} = {value} with the default parameters")
            raise ModelError(f"rest length is {shown}; the spring's force is k (|d| - L) / L, "
                             "so L must be "
                             "positive (for a spring of zero rest length use model.force with "
                             "-k d)", item=spring.label(), line=spring.line)


def _check_coordinates_used(model: Model) -> None:
    used = set()
    for particle in model.particles:
        used |= particle.position.free_symbols
    for c in model.coordinates:
        if c.symbol not in used:
            raise ModelError("does not appear in any particle position X(q, t), so it has no "
                             "mass and its acceleration is undefined; use it in X or remove it",
                             item=c.label(), line=c.line)


def validate(model: Model) -> None:
    """Raises ModelError for the first problem found, naming the item and its line."""
    if not model.coordinates:
        raise ModelError("the model declares no coordinates; add model.coordinate(...)",
                         item="model", line=model.line)
    if not model.particles and model.links:
        raise ModelError("no link of the robot has a mass: give at least one link an "
                         "<inertial> with <mass> and <inertia> (or model.body(...) in a model "
                         "file)", item="model", line=model.line)
    if not model.particles:
        raise ModelError("the model declares no particles; add model.particle(...)",
                         item="model", line=model.line)
    _check_names(model)
    _check_descriptions(model)
    _check_connections(model)
    defaults = _default_values(model)
    _check_expressions(model, defaults)
    _check_rest_lengths(model, defaults)
    _check_coordinates_used(model)
