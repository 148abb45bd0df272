# SPDX-License-Identifier: BSD-3-Clause
"""A model file as the gencoord command sees it: loaded once to learn its options and
parameters, so that `--set name=value` can mean either."""

from __future__ import annotations

import os
from dataclasses import dataclass

from gencoord.derive.maximal_constraints import maximal_constraint_problem
from gencoord.generate.load import load_model
from gencoord.dsl.model import Model
from gencoord.naming import type_name

from gencoord.tool.driver_build import ModelTarget
from gencoord.tool.errors import ToolError


@dataclass
class LoadedModel:
    model: Model
    docstring: str
    target: ModelTarget                 # the model with its build options
    parameters: dict[str, str]          # run-time parameter values from --set


def split_settings(pairs: list[str]) -> dict[str, str]:
    settings = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key or not value:
            raise ToolError(f"--set expects name=value, got '{pair}'")
        settings[key] = value
    return settings


def load(path: str, settings: dict[str, str], stem: str | None = None) -> LoadedModel:
    """Loads `path` with the settings that are its build options; the other settings must
    be its parameters. `stem` (--name) replaces the file's stem in the model's name."""
    model, name, docstring = load_model(path, name=stem)
    option_names = set(model.options)
    options = {k: v for k, v in settings.items() if k in option_names}
    if options:
        model, name, docstring = load_model(path, options, name=stem)
    parameter_names = {p.name for p in model.parameters}
    parameters = {k: v for k, v in settings.items() if k not in option_names}
    unknown = sorted(set(parameters) - parameter_names)
    if unknown:
        known = ", ".join([*model.options, *sorted(parameter_names)]) or "none"
        raise ToolError(f"{path}: --set {', '.join(unknown)}: not an option or a parameter of "
                        f"this model (it has: {known})")
    target = ModelTarget(path=os.path.abspath(path), options=options, name=name,
                         class_name=type_name(name), stem=stem)
    return LoadedModel(model=model, docstring=docstring, target=target, parameters=parameters)


def refuse_unsupported_kinds(loaded, command: str) -> None:
    """For python and crosscheck, a model with both free or ball joints and kinematic
    constraints, which their programs do not take; for crosscheck, kinematic constraints that
    have no maximal form."""
    model = loaded.model
    if command == "crosscheck" and model.has_kinematic_constraints:
        problem = maximal_constraint_problem(model)
        if problem:
            raise ToolError(f"{loaded.target.path}: gencoord crosscheck: {problem}")
    if model.has_generalized_speeds and model.has_kinematic_constraints:
        raise ToolError(f"{loaded.target.path}: gencoord {command} does not take a model with "
                        "both free or ball joints (generalized speeds) and kinematic "
                        "constraints yet; its header does, from C++")
