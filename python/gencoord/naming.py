# SPDX-License-Identifier: BSD-3-Clause
"""The names generated code takes from a model: the header's (model_name, chart_name) and the
C++ type's (type_name). Imports neither SymPy nor Jinja2."""

from __future__ import annotations

import os
import re


def model_name(path: str, options: dict, stem: str | None = None) -> str:
    """The generated model's name: the file stem (or `stem`), plus each option's value
    (`chain_5`; a minus sign is spelled `m`: `scale_m1_5`)."""
    stem = stem or os.path.splitext(os.path.basename(path))[0]
    suffix = "".join(f"_{value}".replace("-", "m") for value in options.values())
    return re.sub(r"[^A-Za-z0-9_]", "_", stem + suffix)


def chart_name(name: str, model, chart) -> str:
    """The name of `chart` of the model `name`: the first chart (`model` itself) keeps the
    model's name; the others append their chart name."""
    return name if chart is model else f"{name}_{chart.chart}"


def type_name(name: str) -> str:
    """CamelCase C++ type of a model name: n_link_chain_5 -> NLinkChain5."""
    return "".join(part[:1].upper() + part[1:] for part in name.split("_") if part)
