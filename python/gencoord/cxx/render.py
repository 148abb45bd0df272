# SPDX-License-Identifier: BSD-3-Clause
"""Renders optimized kernels through the Jinja2 templates (reserved_names.py reads their C++
text for the names a model may not use)."""

from __future__ import annotations

import contextlib
import functools
import hashlib
import math
import os
import tempfile
from typing import Any, Sequence

import jinja2
import sympy as sp

from gencoord import __version__
from gencoord.options import GenerateOptions
from gencoord.library_versions import JINJA2_CACHE_IS_SAFE
from gencoord.cxx.template_views import kernel_view
from gencoord.cxx.line_wrap import LINE_WIDTH, wrap_long_lines, wrap_prose
from gencoord.naming import type_name
from gencoord.cxx.reserved_names import TEMPLATE_DIR
from gencoord.cxx.escapes import backslash_escaped, shell_word
from gencoord.cxx.storage import model_types, needs_heap_matrix

MODEL_TEMPLATE = "model.hpp.j2"
INSTANTIATION_TEMPLATE = "instantiation.cpp.j2"

_RETURN_DOCS = {
    "mass_matrix": "Mt (nv x nv)", "applied_forces": "Ft (nv)", "inertial_forces": "Fi (nv)",
    "forces": "Ft + Fi (nv)", "kinetic_energy": "T", "potential_energy": "V",
    "energy": "T + V", "positions": "x (nx)", "velocities": "xdot (nx)",
    "jacobian": "J (nx x nv)", "bias_acceleration": "gamma (nx)",
    "linear_momentum": "p (dim)", "angular_momentum": "L (angular_dim)",
    "particle_masses": "masses (num_particles)",
    "fixed_point_positions": "fixed-point positions (dim * num_fixed_points)",
    "generalized_forces": "Q (nv)", "input_matrix": "B = dFt/du (nv x num_inputs)",
    "inverse_dynamics": "r = tau (nv)", "qddot": "qddot (nv)",
    "coordinate_rates": "dq/dt (nq)",
    "generalized_potential_energy": "V_q", "external_forces": "F (nx)",
    "penalty_forces": "F_penalty (nx)", "force_jacobian_x": "values (jacobian_x_nonzeros)",
    "force_jacobian_xdot": "values (jacobian_xdot_nonzeros)",
    "penalty_energy": "V_penalty", "constraint_violations": "C (num_constraints)",
    "mass_matrix_product": "Mt qdd (nv)", "jacobian_product": "J dq (nx)",
    "residual_derivative_q": "dr/dq dq (nv)", "residual_derivative_v": "dr/dv dv (nv)",
    "holonomic_constraints": "C (num_holonomic_constraints)",
    "holonomic_jacobian": "dC/dq (num_holonomic_constraints x nq)",
    "constraint_jacobian": "A (num_constraints x nv)",
    "constraint_velocities": "A v + b (num_constraints)",
    "constraint_bias": "gamma (num_constraints)",
}


def dedent(text: str, columns: int) -> str:
    """Removes up to `columns` leading spaces from every line (code written for a class body,
    placed at namespace scope)."""
    return "\n".join(line[min(columns, len(line) - len(line.lstrip(" "))):]
                     for line in text.split("\n"))


_ENVIRONMENT_OPTIONS: dict[str, Any] = dict(
    undefined=jinja2.StrictUndefined,  # a template typo fails instead of emitting ""
    trim_blocks=True, lstrip_blocks=True, keep_trailing_newline=True,
    autoescape=False, extensions=["jinja2.ext.do"])


class _TemplateCache(jinja2.FileSystemBytecodeCache):
    """Jinja2's cache of compiled templates, where an entry that cannot be written (a full
    disk) only means compiling again. Jinja2 itself writes each entry to a temporary file and
    renames it, so a parallel generator (make -j) never reads half of one, and treats an
    entry it cannot read as missing (compat.JINJA2_CACHE_IS_SAFE: only in 3.1.2 and later)."""

    def dump_bytecode(self, bucket: jinja2.bccache.Bucket) -> None:
        with contextlib.suppress(OSError):
            super().dump_bytecode(bucket)


def _bytecode_cache() -> jinja2.BytecodeCache | None:
    """The per-user cache of compiled templates, in the temporary folder: compiling the
    templates takes about 0.1 s, a tenth of generating a 10-link chain, loading them 2 ms.

    Jinja2 checks each entry against the template's text; the file name also holds a hash of
    the Jinja2 version and our environment options, which change the compiled code too. None
    (compile every time) where there is no temporary folder of its own, or where Jinja2 is
    too old to share the cache safely between parallel generators."""
    if not JINJA2_CACHE_IS_SAFE:
        return None
    if os.path.realpath(tempfile.gettempdir()) == os.path.realpath(os.getcwd()):
        return None  # Python's last resort; the cache would land in the working folder
    key = hashlib.sha1(repr((jinja2.__version__, sorted(_ENVIRONMENT_OPTIONS.items(), key=str)))
                       .encode()).hexdigest()[:12]
    try:
        return _TemplateCache(pattern=f"__gencoord_{key}_%s.cache")
    except (OSError, RuntimeError):
        return None


@functools.lru_cache(maxsize=None)  # one per process: each template is compiled once
def _environment() -> jinja2.Environment:
    environment = jinja2.Environment(loader=jinja2.FileSystemLoader(TEMPLATE_DIR),
                                     bytecode_cache=_bytecode_cache(), **_ENVIRONMENT_OPTIONS)
    environment.filters["dedent"] = dedent
    environment.filters["cxx_string"] = cxx_string_literal
    return environment


def cxx_string_literal(text: str, indent: int) -> str:
    """`text` as a C++ string literal (quotes, backslashes and control characters escaped)
    on a line indented by `indent` columns, with room for a comma after it; a longer text
    becomes adjacent literals ("..." "..."), one per line, cut after spaces."""
    room = LINE_WIDTH - indent - 3  # the quotes and a comma
    pieces, current = [], ""
    for word in backslash_escaped(text, '"\\').split(" "):
        candidate = word if not current else current + " " + word
        if current and len(candidate) > room:
            pieces.append(current + " ")
            current = word
        else:
            current = candidate
    pieces.append(current)
    return ("\n" + " " * indent).join(f'"{piece}"' for piece in pieces)


def _format_default(value: float) -> str:
    text = repr(float(value))
    return text if ("." in text or "e" in text or "n" in text) else text + ".0"


def instantiation_file_name(name: str, group: int) -> str:
    """The source file that compiles part group `group` of model `name` for double."""
    return f"{name}_double_{group}.cpp"


def _part_groups(kernels) -> list[int]:
    """The translation-unit groups the parts of these kernels fall in (split.assign_groups)."""
    return sorted({part.group for k in kernels for part in k.parts if part.group is not None})


def _limits_view(model) -> list[dict]:
    """Each joint limit's coordinate and speed (indices in q and v), ends and ratings."""
    speeds = [s.symbol for s in model.speeds]

    def end(value: float) -> str:
        if math.isinf(value):
            return f"{'-' if value < 0 else ''}std::numeric_limits<double>::infinity()"
        return _format_default(value)

    return [dict(name=limit.name, coordinate=model.coordinates.index(limit.coordinate),
                 speed=speeds.index(limit.coordinate.rate), lower=end(limit.lower),
                 upper=end(limit.upper), velocity=end(limit.velocity),
                 effort=end(limit.effort))
            for limit in model.limits]


def _coordinate_speeds(model) -> list[int]:
    """For each coordinate, the index in v of the speed that is its rate, or -1 for a free or
    ball joint's coordinate, whose rate combines its joint's speeds."""
    speeds = [s.symbol for s in model.speeds]
    return [speeds.index(c.rate) if c.rate in speeds else -1 for c in model.coordinates]


def _chart_context(chart, first, unroll_max_nq: int) -> dict:
    """The template context of one chart (gencoord/cxx/templates/model_struct.j2)."""
    model, optimized, n = chart.model, chart.optimized, chart.num_reduced_kernels
    nq, nv = model.nq, model.nv
    generalized = model.has_generalized_speeds
    velocities = f"speeds (nv = {nv})" if generalized else f"generalized velocities (nq = {nq})"
    owner = type_name(chart.name)
    offsets = range(0, model.dim * len(model.particles), model.dim)
    return dict(
        name=chart.name, type_name=owner, nq=nq, nv=nv, dim=model.dim,
        unroll_max_nq=unroll_max_nq,
        params_from=None if chart is first else type_name(first.name),
        num_particles=len(model.particles), nx=model.dim * len(model.particles),
        types=model_types(nq, nv, model.dim * len(model.particles)),
        speeds=([dict(name=s.name, description=s.description) for s in model.speeds]
                if generalized else []),
        quaternions=model.quaternions,
        coordinate_speeds=_coordinate_speeds(model) if generalized else [],
        limits=_limits_view(model),
        kinematic_constraints=[dict(name=c.name, holonomic=k < len(model.holonomic_constraints))
                               for k, c in enumerate([*model.holonomic_constraints,
                                                      *model.velocity_constraints])],
        initial_v=[_format_default(s.initial) for s in model.speeds],
        coordinates=[dict(name=c.name, description=c.description,
                          initial=_format_default(c.initial),
                          initial_rate=_format_default(c.initial_rate))
                     for c in model.coordinates],
        particles=[dict(name=p.name, mass=str(p.mass), offset=o)
                   for p, o in zip(model.particles, offsets)],
        fixed_points=[dict(name=p.name, offset=model.dim * k)
                      for k, p in enumerate(model.fixed_points)],
        parameters=[dict(name=p.name, default=_format_default(p.default),
                         description=p.description) for p in model.parameters],
        inputs=[dict(name=p.name, description=p.description) for p in model.inputs],
        kernels=[kernel_view(k, owner) for k in optimized.kernels[:n]],
        maximal_kernels=[kernel_view(k, owner + "::Maximal") for k in optimized.kernels[n:]],
        part_groups=_part_groups(optimized.kernels[:n]),
        maximal_part_groups=_part_groups(optimized.kernels[n:]),
        has_maximal=chart.maximal is not None,
        no_maximal=chart.no_maximal,
        constraint_names=chart.maximal.constraint_names if chart.maximal else [],
        declared_constraints=chart.maximal.declared_constraints if chart.maximal else 0,
        has_generalized_forces=bool(model.generalized_forces),
        forces_have_potential=chart.forces_have_potential,
        dissipative=chart.dissipative,
        recursive_qddot=chart.paths.recursive_qddot,
        jacobian_x=chart.maximal.force_jacobian_x if chart.maximal else [],
        jacobian_xdot=chart.maximal.force_jacobian_xdot if chart.maximal else [],
        input_docs={"q": f"generalized coordinates (nq = {nq})",
                    "v": velocities, "t": "time",
                    "qdd": (f"accelerations dv/dt (nv = {nv})" if generalized
                            else f"generalized accelerations (nq = {nq})"),
                    "dq": f"a direction in q (nq = {nq})",
                    "dv": f"a direction in v (nv = {nv})" if generalized
                          else f"a direction in v (nq = {nq})",
                    "pos": "particle positions x, stacked (nx)",
                    "vel": "particle velocities xdot, stacked (nx)",
                    "kappa": "penalty stiffness (rods: force per strain; pins, planes: N/m)",
                    "penalty_damping": "penalty damping coefficient"},
    )


def render_model(charts: list, name: str, docstring: str, source_path: str, header_path: str,
                 analysis: list[str], flags: Sequence[str] = (), translation_units: int = 0,
                 unroll_max_nq: int = GenerateOptions.unroll_max_nq) -> str:
    """The text of generated/<name>.hpp: one struct per chart (pipeline.GeneratedChart).

    Of each chart's `optimized.kernels`, the first `num_reduced_kernels` belong to the reduced
    model, the rest to its nested maximal-coordinate model. With several charts the first
    owns the Params type and an atlas struct lists them all. With `translation_units` the
    parts (which have their groups) are members of class templates Parts<group>, declared
    extern template for double (render_instantiation writes their definitions). qddot's
    solve is unrolled up to `unroll_max_nq` coordinates.
    """
    model = charts[0].model
    chart_contexts = [_chart_context(chart, charts[0], unroll_max_nq) for chart in charts]
    context = dict(
        header_path=header_path, source_path=source_path, template_name=MODEL_TEMPLATE,
        version=__version__, sympy_version=sp.__version__,
        options=[shell_word(f"{key}={value}") for key, value in model.options.items()],
        flags="".join(" " + flag for flag in flags),  # generator flags other than defaults
        # the docstring goes in a /* */ comment, each line after " * ": keep it from closing
        # early, and wrap it here (wrap_long_lines breaks code, not prose)
        docstring=[piece for line in docstring.splitlines()
                   for piece in wrap_prose(line.rstrip().replace("*/", "* /"), LINE_WIDTH - 3)],
        analysis=analysis,
        total_ops=sum(c.optimized.total_ops for c in charts),
        intermediate_count=sum(c.optimized.intermediate_count for c in charts),
        output_count=sum(c.optimized.output_count for c in charts),
        charts=chart_contexts,
        atlas=dict(name=name, type_name=type_name(name) + "Atlas",
                   chart_names=[c.model.chart for c in charts]) if len(charts) > 1 else None,
        return_docs=_RETURN_DOCS,
        any_split=any(k.parts for c in charts for k in c.optimized.kernels),
        any_sin_cos=any(k.sin_cos or any(p.sin_cos for p in k.parts)
                        for c in charts for k in c.optimized.kernels),
        heap_matrix=any(needs_heap_matrix(chart["types"]) for chart in chart_contexts),
        translation_units=translation_units,
        instantiation_files=[instantiation_file_name(name, g) for g in range(translation_units)],
    )
    return wrap_long_lines(_environment().get_template(MODEL_TEMPLATE).render(**context))


def render_instantiation(charts: list, name: str, source_path: str, flags: list[str],
                         group: int, translation_units: int) -> str:
    """The text of generated/<name>_double_<group>.cpp: the explicit instantiation for double
    of every chart's part group `group` (render_model with `translation_units`)."""
    model = charts[0].model
    context = dict(
        file_name=instantiation_file_name(name, group), header=f"{name}.hpp",
        name=name, source_path=source_path, template_name=INSTANTIATION_TEMPLATE,
        version=__version__, sympy_version=sp.__version__,
        options=[shell_word(f"{key}={value}") for key, value in model.options.items()],
        flags="".join(" " + flag for flag in flags),
        group=group, translation_units=translation_units,
        structs=[struct for c in charts for struct, kernels in (
                     (type_name(c.name), c.optimized.kernels[:c.num_reduced_kernels]),
                     (type_name(c.name) + "::Maximal",
                      c.optimized.kernels[c.num_reduced_kernels:]))
                 if group in _part_groups(kernels)],
    )
    return wrap_long_lines(
        _environment().get_template(INSTANTIATION_TEMPLATE).render(**context))
