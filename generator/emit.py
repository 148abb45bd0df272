"""Renders optimized kernels through the Jinja2 templates: the only module that knows them."""

from __future__ import annotations

import os

import jinja2
import sympy as sp

from . import __version__
from .maximal import MaximalDerivation
from .model import Model
from .optimize import OptimizedModel

TEMPLATE_DIR = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                            "templates")
MODEL_TEMPLATE = "model.hpp.j2"

_INPUT_TYPES = {"q": "const QVector<Scalar>& ", "v": "const QVector<Scalar>& ",
                "qdd": "const QVector<Scalar>& ",
                "t": "const Scalar& ", "pos": "const XVector<Scalar>& ",
                "vel": "const XVector<Scalar>& ", "kappa": "const Scalar& ",
                "penalty_damping": "const Scalar& "}
_RETURN_DOCS = {
    "mass_matrix": "Mt (nq x nq)", "applied_forces": "Ft (nq)", "inertial_forces": "Fi (nq)",
    "forces": "Ft + Fi (nq)", "kinetic_energy": "T", "potential_energy": "V",
    "energy": "T + V", "positions": "x (nx)", "velocities": "xdot (nx)",
    "jacobian": "J (nx x nq)", "bias_acceleration": "gamma (nx)",
    "linear_momentum": "p (dim)", "angular_momentum": "L (angular_dim)",
    "particle_masses": "masses (num_particles)", "generalized_forces": "Q (nq)",
    "inverse_dynamics": "r = tau (nq)",
    "generalized_potential_energy": "V_q", "external_forces": "F (nx)",
    "penalty_forces": "F_penalty (nx)", "force_jacobian_x": "values (jacobian_x_nonzeros)",
    "force_jacobian_xdot": "values (jacobian_xdot_nonzeros)",
    "penalty_energy": "V_penalty", "constraint_violations": "C (num_constraints)",
}


def type_name(name: str) -> str:
    """CamelCase C++ type of a model name: n_link_chain_5 -> NLinkChain5."""
    return "".join(part[:1].upper() + part[1:] for part in name.split("_") if part)


LINE_WIDTH = 100
CONTINUATION_INDENT = 8


def wrap_expression(code: str, first_column: int) -> str:
    """Breaks a long C++ expression before top-level + and - so lines stay readable.

    `first_column` is where the expression starts on its first line; continuation lines are
    indented by CONTINUATION_INDENT. Deterministic, and only whitespace changes.
    """
    if first_column + len(code) <= LINE_WIDTH - 1:
        return code
    pieces, depth, start = [], 0, 0
    for k, char in enumerate(code):
        if char == "(":
            depth += 1
        elif char == ")":
            depth -= 1
        elif depth == 0 and char in "+-" and code[k - 1:k] == " " and code[k + 1:k + 2] == " ":
            pieces.append(code[start:k - 1])
            start = k
    pieces.append(code[start:])
    lines, current, column = [], pieces[0], first_column
    for piece in pieces[1:]:
        if column + len(current) + 1 + len(piece) > LINE_WIDTH - 1:
            lines.append(current)
            current, column = piece, CONTINUATION_INDENT
        else:
            current += " " + piece
    lines.append(current)
    return ("\n" + " " * CONTINUATION_INDENT).join(lines)


def _environment() -> jinja2.Environment:
    environment = jinja2.Environment(
        loader=jinja2.FileSystemLoader(TEMPLATE_DIR),
        undefined=jinja2.StrictUndefined,  # a template typo fails instead of emitting ""
        trim_blocks=True, lstrip_blocks=True, keep_trailing_newline=True,
        autoescape=False, extensions=["jinja2.ext.do"])
    environment.filters["wrap"] = wrap_expression
    return environment


def _format_default(value: float) -> str:
    text = repr(float(value))
    return text if ("." in text or "e" in text or "n" in text) else text + ".0"


def render_model(model: Model, name: str, docstring: str, source_path: str,
                 header_path: str, optimized: OptimizedModel, num_reduced_kernels: int,
                 maximal: MaximalDerivation, analysis: list[str]) -> str:
    """The text of generated/<name>.hpp.

    The first `num_reduced_kernels` of `optimized.kernels` belong to the reduced model, the
    rest to its nested maximal-coordinate model.
    """
    nq = model.nq
    offsets = range(0, model.dim * len(model.particles), model.dim)
    context = dict(
        header_path=header_path, source_path=source_path, template_name=MODEL_TEMPLATE,
        version=__version__, sympy_version=sp.__version__,
        options=[(k, v) for k, v in model.options.items()],
        # the docstring goes in a /* */ comment: keep it from closing early
        docstring=[line.rstrip().replace("*/", "* /") for line in docstring.splitlines()],
        analysis=analysis, total_ops=optimized.total_ops, intermediate_count=optimized.intermediate_count,
        output_count=optimized.output_count,
        name=name, type_name=type_name(name), nq=nq, dim=model.dim,
        num_particles=len(model.particles), nx=model.dim * len(model.particles),
        coordinates=[dict(name=c.name, description=c.description,
                          initial=_format_default(c.initial),
                          initial_rate=_format_default(c.initial_rate))
                     for c in model.coordinates],
        particles=[dict(name=p.name, mass=str(p.mass), offset=o)
                   for p, o in zip(model.particles, offsets)],
        parameters=[dict(name=p.name, default=_format_default(p.default),
                         description=p.description) for p in model.parameters],
        kernels=optimized.kernels[:num_reduced_kernels],
        maximal_kernels=optimized.kernels[num_reduced_kernels:],
        constraint_names=maximal.constraint_names,
        has_generalized_forces=bool(model.generalized_forces),
        jacobian_x=maximal.force_jacobian_x, jacobian_xdot=maximal.force_jacobian_xdot,
        input_types=_INPUT_TYPES, return_docs=_RETURN_DOCS,
        input_docs={"q": f"generalized coordinates (nq = {nq})",
                    "v": f"generalized velocities (nq = {nq})", "t": "time",
                    "qdd": f"generalized accelerations (nq = {nq})",
                    "pos": "particle positions x, stacked (nx)",
                    "vel": "particle velocities xdot, stacked (nx)",
                    "kappa": "penalty stiffness (rods: force per strain; pins, planes: N/m)",
                    "penalty_damping": "penalty damping coefficient"},
    )
    return _environment().get_template(MODEL_TEMPLATE).render(**context)
