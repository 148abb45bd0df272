"""Checks a loaded model before anything is derived; each failure names the item and line."""

from __future__ import annotations

import re

import sympy as sp
from sympy.core.function import AppliedUndef

from .errors import ModelError
from .model import Model, Pin, Rod

CXX_KEYWORDS = frozenset("""
alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t char16_t
char32_t class compl concept const consteval constexpr constinit const_cast continue co_await
co_return co_yield decltype default delete do double dynamic_cast else enum explicit export
extern false float for friend goto if inline int long mutable namespace new noexcept not
not_eq nullptr operator or or_eq private protected public register reinterpret_cast requires
return short signed sizeof static static_assert static_cast struct switch template this
thread_local throw true try typedef typeid typename union unsigned using virtual void volatile
wchar_t while xor xor_eq final override
""".split())

# Names the generated code itself uses inside kernels; a user name must not shadow them.
RESERVED_NAMES = frozenset({
    "q", "v", "t", "params", "Scalar", "result", "Mt", "f", "ok", "std", "Eigen", "sin", "cos",
    "tan", "sqrt", "exp", "log", "pow", "abs", "atan2", "asin", "acos", "atan", "sinh", "cosh",
    "tanh", "Params", "name", "nq", "nx", "dim", "pos", "vel", "kappa", "penalty_damping",
    "Maximal", "qdd", "dr_dq", "dr_dv", "carried",
    # the raw output pointers of kernel parts (lvalues.data_pointer)
    "result_data", "Mt_data", "f_data", "dr_dq_data", "dr_dv_data",
})
_IDENTIFIER = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")
_TEMPORARY = re.compile(r"^tmp[0-9]+$")


def _check_name(name: str, label: str, line: int | None) -> None:
    if not isinstance(name, str) or not _IDENTIFIER.match(name):
        raise ModelError("names must start with a letter and contain only letters, digits and "
                         "underscores, so they can be C++ identifiers", item=label, line=line)
    if name in CXX_KEYWORDS:
        raise ModelError(f"'{name}' is a C++ keyword and cannot name generated code; rename it",
                         item=label, line=line)
    if name in RESERVED_NAMES or _TEMPORARY.match(name) or "__" in name:
        raise ModelError(f"'{name}' is reserved by the generated code; rename it",
                         item=label, line=line)


def _check_names(model: Model) -> None:
    seen: dict[str, str] = {}
    symbols = [*model.coordinates, *model.parameters]
    for item in [*symbols, *model.particles, *model.fixed_points]:
        _check_name(item.name, item.label(), item.line)
        if item.name in seen:
            raise ModelError(f"the name '{item.name}' is already used by {seen[item.name]}; "
                             "give each item its own name", item=item.label(), line=item.line)
        seen[item.name] = item.label()
    for c in model.coordinates:
        for derived in (c.rate.name, c.acceleration.name):
            if derived in seen:
                raise ModelError(f"'{derived}' is a derivative of {c.label()}; rename the "
                                 "other item", item=seen[derived], line=c.line)


def _check_symbols(expr, allowed: set, label: str, line: int | None, hint: str) -> None:
    expr = sp.sympify(expr)
    functions = sorted(str(f) for f in expr.atoms(AppliedUndef))
    if functions:
        raise ModelError(f"uses {', '.join(functions)}: a function SymPy cannot evaluate; "
                         "write it with elementary functions (sin, exp, sqrt ...)",
                         item=label, line=line)
    unknown = expr.free_symbols - allowed
    if not unknown:
        return
    names = sorted(str(s) for s in unknown)
    allowed_names = {str(a) for a in allowed}
    lookalikes = sorted(name for name in names if name in allowed_names)
    if lookalikes:
        raise ModelError(f"uses a symbol {', '.join(lookalikes)} made outside the model, not the "
                         "one the model declared under that name; use the symbol that "
                         "model.parameter() or model.coordinate() returned", item=label, line=line)
    raise ModelError(f"uses {', '.join(names)}, which {'is' if len(names) == 1 else 'are'}"
                     f" not declared; {hint}", item=label, line=line)


def _check_expressions(model: Model) -> None:
    params = {p.symbol for p in model.parameters}
    q = {c.symbol for c in model.coordinates}
    rates = {c.rate for c in model.coordinates}
    t = {model.time}
    point_symbols = set()
    for point in model.points:
        point_symbols |= set(point.x) | set(point.xdot)
    declare = "declare it with model.parameter() or model.coordinate()"

    for particle in model.particles:
        _check_symbols(particle.position, q | t | params, f"{particle.label()} position",
                       particle.line, declare)
        _check_symbols(particle.mass, q | t | params, f"{particle.label()} mass",
                       particle.line, declare)
        depends = sorted(str(s) for s in particle.mass.free_symbols & (q | t))
        if depends:
            raise ModelError(f"mass depends on {', '.join(depends)}; a particle's mass must be "
                             "a constant or a parameter", item=particle.label(), line=particle.line)
        _check_positive_mass(model, particle)
    for point in model.fixed_points:
        _check_symbols(point.position, t | params, f"{point.label()} position", point.line,
                       "a fixed point may depend only on parameters and t")
    for item in model.gravities:
        _check_symbols(item.acceleration, t | params, item.label(), item.line, declare)
    for spring in model.springs:
        for what, expr in (("stiffness", spring.stiffness), ("rest length", spring.rest_length),
                           ("damping", spring.damping)):
            _check_symbols(expr, t | params, f"{spring.label()} {what}", spring.line,
                           "spring constants may depend only on parameters and t")
    for damper in model.dampers:
        _check_symbols(damper.coefficient, t | params, damper.label(), damper.line, declare)
    for force in model.particle_forces:
        _check_symbols(force.force, point_symbols | t | params, force.label(), force.line,
                       "a particle force may use points' .x and .xdot, t and parameters")
        if force.potential is not None:
            _check_symbols(force.potential, point_symbols | t | params, force.label(),
                           force.line, "a potential may use points' .x, t and parameters")
    for force in model.generalized_forces:
        _check_symbols(force.force, q | rates | t | params, force.label(), force.line,
                       "a generalized force may use coordinates, model.rate(q), t, parameters")
        if force.potential is not None:
            _check_symbols(force.potential, q | t | params, f"{force.label()} potential",
                           force.line, "a potential may use coordinates, t and parameters")
    _check_constraint_expressions(model, t | params)


def _check_constraint_expressions(model: Model, allowed: set) -> None:
    """Rod lengths, pin anchors and plane normals and offsets: parameters and t only."""
    hint = "a constraint may depend only on parameters and t"
    for constraint in model.constraints:
        if isinstance(constraint, Rod):
            parts = [("length", constraint.length)]
        elif isinstance(constraint, Pin):
            parts = [("anchor", constraint.anchor)]
        else:
            parts = [("normal", constraint.normal), ("offset", constraint.offset)]
        for what, expr in parts:
            _check_symbols(expr, allowed, f"{constraint.label()} {what}", constraint.line, hint)


def _check_positive_mass(model: Model, particle) -> None:
    # xreplace, not subs: subs tries every parameter of a 100-link chain on every mass
    defaults = {p.symbol: sp.sympify(p.default) for p in model.parameters}
    value = particle.mass.xreplace(defaults)
    if not value.is_number or not bool(value > 0):
        raise ModelError(f"mass is {particle.mass} = {value} with the default parameters; "
                         "a particle's mass must be positive", item=particle.label(),
                         line=particle.line)


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
    if not model.particles:
        raise ModelError("the model declares no particles; add model.particle(...)",
                         item="model", line=model.line)
    _check_names(model)
    _check_expressions(model)
    _check_coordinates_used(model)
