# SPDX-License-Identifier: BSD-3-Clause
"""Checks that the charts of an atlas describe one system in different coordinates.

The runtime maps a state from one chart to another through the particle positions x and
velocities xdot, so the charts must agree on everything that is a function of (x, xdot, t):
the particles and their masses, the parameters, gravity, springs, dampers and forces on
particles. Forces acting directly on q (generalized forces, joint springs) belong to one
chart's coordinates and have no meaning in another, so an atlas refuses them.
"""

from __future__ import annotations

import re

import sympy as sp

from gencoord.errors import ModelError
from gencoord.dsl.model import Model

_CHART_NAME = re.compile(r"^[a-z][a-z0-9_]*$")


def _point_names(model: Model) -> dict:
    """Point x/xdot symbols -> a chart-independent spelling (the point's name)."""
    names = {}
    for point in model.points:
        for axis, (x, xdot) in enumerate(zip(point.x, point.xdot)):
            names[x] = sp.Symbol(f"x_{point.name}_{axis}")
            names[xdot] = sp.Symbol(f"xdot_{point.name}_{axis}")
    return names


def _signature(model: Model) -> dict[str, list[str]]:
    """Everything a chart must share with the others, as comparable strings."""
    names = _point_names(model)

    def text(expr) -> str:
        return str(sp.sympify(expr).xreplace(names))

    return {
        "dimension": [str(model.dim)],
        "particles (names and masses)": [f"{p.name}: {text(p.mass)}" for p in model.particles],
        "parameters (names and defaults)": [f"{p.name} = {p.default!r}"
                                            for p in model.parameters],
        "gravity": [str(list(g.acceleration)) for g in model.gravities],
        "springs": [f"{s.a.name}-{s.b.name}: k={text(s.stiffness)} L={text(s.rest_length)} "
                    f"c={text(s.damping)}" for s in model.springs],
        "dampers": [f"{d.a.name}-{d.b.name}: {text(d.coefficient)}" for d in model.dampers],
        "forces on particles": [f"{f.particle.name}: {text(list(f.force))}"
                                for f in model.particle_forces],
    }


def check_atlas(model: Model) -> None:
    """Raises ModelError naming the chart and what differs; a model without charts passes."""
    if not model.charts:
        return
    first = _signature(model)
    for chart in [model, *model.charts]:
        assert chart.chart is not None  # add_chart refuses a chart without a name
        label = f"chart '{chart.chart}'"
        if not _CHART_NAME.match(chart.chart):
            raise ModelError("chart names are lower-case letters, digits and underscores "
                             "(they name C++ types and files)", item=label, line=chart.line)
        if chart.has_generalized_speeds:
            raise ModelError("an atlas's charts cannot have free or ball joints: their unit "
                             "quaternions have no singular set, so one chart is enough",
                             item=label, line=chart.line)
        if chart.generalized_forces:
            raise ModelError("an atlas cannot have forces acting directly on q (generalized "
                             "forces, joint springs): they depend on one chart's coordinates; "
                             "write them as forces on particles", item=label, line=chart.line)
        if chart.options:
            raise ModelError("declare options on the first chart only", item=label,
                             line=chart.line)
        for what, values in _signature(chart).items():
            if values != first[what]:
                raise ModelError(
                    f"its {what} differ from chart '{model.chart}': {values} vs {first[what]}; "
                    "every chart must describe the same particles, parameters and forces",
                    item=label, line=chart.line)
