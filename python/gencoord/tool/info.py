# SPDX-License-Identifier: BSD-3-Clause
"""`gencoord info MODEL.py`: what a model file declares, without generating or building."""

from __future__ import annotations

import os

import sympy as sp

from gencoord.tool.layout import cache_dir
from gencoord.tool.model_file import LoadedModel

_LABEL_WIDTH = 13


def _row(label: str, text: str) -> str:
    return f"{label:<{_LABEL_WIDTH}}{text}"


def _names(items) -> str:
    return ", ".join(item.name for item in items) or "none"


def _expression(value) -> str:
    return sp.sstr(value) if isinstance(value, sp.Basic) else repr(value)


def describe(loaded: LoadedModel) -> list[str]:
    model, target = loaded.model, loaded.target
    lines = [_row("model", f"{target.name} ({os.path.relpath(target.path)}), "
                           f"{model.dim}D, nq = {len(model.coordinates)}"
                           + (f", nv = {model.nv}" if model.has_generalized_speeds else ""))]
    summary = loaded.docstring.split("\n\n", 1)[0]  # the docstring's first paragraph
    for text in summary.splitlines():
        lines.append(_row("", text.strip()))
    lines.append(_row("C++", f"gencoord::models::{target.class_name} in "
                             f"generated/{target.name}.hpp"))
    for k, (name, value) in enumerate(model.options.items()):
        lines.append(_row("options" if k == 0 else "", f"{name} = {value}"))
    for k, c in enumerate(model.coordinates):
        lines.append(_row("coordinates" if k == 0 else "",
                          f"{c.name}: {c.description} (initial {c.initial:g}"
                          + (f", rate {c.initial_rate:g})" if c.has_speed else ")")))
    for k, speed in enumerate(model.joint_speeds):  # a free or ball joint's: dq/dt = G(q) v
        lines.append(_row("speeds" if k == 0 else "",
                          f"{speed.name}: {speed.description} (initial {speed.initial:g})"))
    for k, p in enumerate(model.parameters):
        lines.append(_row("parameters" if k == 0 else "",
                          f"{p.name} = {p.default:g}: {p.description}"))
    lines.append(_row("particles", ", ".join(
        f"{p.name} (mass {_expression(p.mass)})" for p in model.particles) or "none"))
    lines.append(_row("fixed points", _names(model.fixed_points)))
    forces = [*model.gravities, *model.springs, *model.dampers, *model.particle_forces,
              *model.generalized_forces]
    lines.append(_row("forces", ", ".join(f.label() for f in forces) or "none"))
    lines.append(_row("constraints", ", ".join(c.label() for c in model.constraints)
                      or "none (the cross-check's maximal model has none to enforce)"))
    kinematic = [*model.holonomic_constraints, *model.velocity_constraints]
    if kinematic:
        lines.append(_row("closures", ", ".join(c.label() for c in kinematic)))
        free = model.nv - len(kinematic)
        lines.append(_row("", f"{free} degree{'s' if free != 1 else ''} of freedom of motion "
                              f"({model.nv} speeds, {len(kinematic)} constraints)"))
    for k, line in enumerate(model.ignored):
        lines.append(_row("not read" if k == 0 else "", line))
    if model.charts:
        names = [model.chart or "", *(c.chart or "" for c in model.charts)]
        lines.append(_row("charts", ", ".join(names)))
    lines.append(_row("cache", cache_dir()))  # where simulate and crosscheck build it
    return lines
