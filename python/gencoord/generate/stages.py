# SPDX-License-Identifier: BSD-3-Clause
"""The stages of one generation, each timed: load, check, analyse, derive, optimize, emit.

`generate` loads the model file, runs the per-chart stages for each chart of its atlas
(`_CHART_STAGES`, each a function of the chart's `_ChartWork`) and renders the header.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, field
from typing import Callable, Optional, Sequence

from gencoord.checks.atlas import check_atlas
from gencoord.derive.body_tree import body_tree
from gencoord.checks.conservative import dissipative, forces_have_potential
from gencoord.checks.constraints import verify_constraints
from gencoord.checks.kinematic_constraints import check_kinematic_constraints
from gencoord.derive.dense import Derivation, Kinematics, derive
from gencoord.generate.dynamics_paths import PathChoice, choose_paths
from gencoord.errors import ModelError
from gencoord.cxx.render import instantiation_file_name, render_instantiation, render_model
from gencoord.cxx.escapes import shell_word
from gencoord.derive.kernel_set import build_kernels, build_maximal_kernels
from gencoord.generate.limits import size_warning
from gencoord.generate.load import load_model
from gencoord.derive.kinematic_constraints import (ConstraintDerivation,
                                                   derive_kinematic_constraints)
from gencoord.derive.looped import looped_outputs
from gencoord.derive.maximal import (KAPPA, PENALTY_DAMPING, MaximalDerivation, derive_maximal,
                                     has_maximal_model, why_no_maximal_model)
from gencoord.dsl.model import Model
from gencoord.naming import chart_name
from gencoord.optimize.optimizer import OptimizedModel, optimize_model
from gencoord.optimize.state import OptimizeOptions
from gencoord.options import GenerateOptions
from gencoord.checks.full_rank import check_full_rank
from gencoord.viewer.scene import scene_json
from gencoord.checks.singularities import analyse_singularities
from gencoord.optimize.split import assign_role_groups, is_derivative_path
from gencoord.derive.point_recursion import RecursiveDynamics
from gencoord.derive.structured import derive_structured
from gencoord.derive.recursions import tree_dynamics
from gencoord.checks.validate import validate


@dataclass
class Generated:
    name: str
    header: str                                   # the header's text
    analysis: list[str]                           # singularity report lines
    timings: list[tuple[str, float]] = field(default_factory=list)
    # with --translation-units N: file name -> text of each <name>_double_<k>.cpp
    sources: dict[str, str] = field(default_factory=dict)
    scene: str = ""                               # <name>.scene.json's text (scene.py)


def working_directory_relative(path: str) -> str:
    """The model path for banners: relative to the directory generation runs in, so the
    banner's regenerate command works from there and does not depend on where it lives."""
    return os.path.relpath(os.path.abspath(path)).replace(os.sep, "/")


def _symbol_names(model: Model) -> tuple[dict, dict]:
    """C++ spellings of every input and parameter symbol, and the input each belongs to."""
    names, input_of = {}, {}
    for c in model.coordinates:
        names[c.symbol], input_of[c.symbol] = c.name, "q"
    for speed in model.speeds:
        names[speed.symbol], input_of[speed.symbol] = speed.symbol.name, "v"
        names[speed.acceleration], input_of[speed.acceleration] = speed.acceleration.name, "qdd"
    for p in model.parameters:
        names[p.symbol] = p.name
    names[model.time], input_of[model.time] = "t", "t"
    for k, symbol in enumerate(s for p in model.particles for s in p.x):
        names[symbol], input_of[symbol] = f"pos({k})", "pos"
    for k, symbol in enumerate(s for p in model.particles for s in p.xdot):
        names[symbol], input_of[symbol] = f"vel({k})", "vel"
    names[KAPPA], input_of[KAPPA] = "kappa", "kappa"
    names[PENALTY_DAMPING], input_of[PENALTY_DAMPING] = "penalty_damping", "penalty_damping"
    return names, input_of


@dataclass
class GeneratedChart:
    """One chart's derivation, optimized and ready for the template."""
    model: Model
    name: str
    optimized: OptimizedModel
    num_reduced_kernels: int
    # None without --maximal, or for a model that can have none (no_maximal says why)
    maximal: MaximalDerivation | None
    analysis: list[str]
    forces_have_potential: bool          # conservative.py: the struct's forces_have_potential
    dissipative: bool                    # conservative.py: the struct's dissipative
    paths: PathChoice                    # dense or recursive qddot and inverse_dynamics
    no_maximal: str = ""                 # why the header has no struct Maximal


@dataclass
class _Observers:
    """Who hears of a generation's progress: each stage's time, and a warning."""
    on_stage: Optional[Callable[[str, float], None]] = None
    on_warning: Optional[Callable[[str], None]] = None
    timings: list[tuple[str, float]] = field(default_factory=list)
    start: float = field(default_factory=time.perf_counter)

    def stage_done(self, label: str) -> None:
        now = time.perf_counter()
        self.timings.append((label, now - self.start))
        if self.on_stage:
            self.on_stage(label, now - self.start)
        self.start = now


@dataclass
class _ChartWork:
    """What the stages of one chart hand on to the next."""
    model: Model                 # the model file's model: the first chart
    chart: Model
    options: GenerateOptions
    kin: Kinematics
    notes: list[str] = field(default_factory=list)
    analysis: list[str] = field(default_factory=list)
    conservative: bool = False
    dissipative: bool = False
    recursive: RecursiveDynamics | None = None  # the tree's recursions (recursions.py)
    tree_derived: bool = False   # every output from the recursions, in O(n) intermediates
    derivation: Derivation | None = None
    definitions: list = field(default_factory=list)
    maximal: MaximalDerivation | None = None
    constraints: ConstraintDerivation | None = None  # the kinematic constraints' equations

    @property
    def small(self) -> bool:
        return self.chart.nq <= self.options.flat_max_nq

    @property
    def large(self) -> bool:
        # looped.py's column loops take v = q' (one direction type for q and v)
        return (self.chart.nq >= self.options.loop_min_nq
                and not self.chart.has_generalized_speeds)


def _check(work: _ChartWork, observers: _Observers) -> None:
    validate(work.chart)
    work.constraints = derive_kinematic_constraints(work.chart, work.kin)
    if work.chart is work.model:
        tree = work.kin.tree is not None or body_tree(work.model) is not None
        warning = size_warning(work.model, tree)
        if warning and observers.on_warning:
            observers.on_warning(warning)
    work.notes = (check_full_rank(work.chart, kin=work.kin)
                  + verify_constraints(work.chart, kin=work.kin)
                  + check_kinematic_constraints(work.chart, work.constraints, work.kin))


def _analyse(work: _ChartWork, observers: _Observers) -> None:
    work.analysis = analyse_singularities(work.chart, kin=work.kin).lines() + work.notes
    work.conservative = forces_have_potential(work.chart, work.kin)
    work.dissipative = dissipative(work.chart, work.conservative)


def _derive(work: _ChartWork, observers: _Observers) -> None:
    chart, dynamics = work.chart, work.options.dynamics
    # --dynamics dense: the dense derivation and kernels, the reference
    # (a large tree's n^2 outputs are loops over its recursions' products: looped.py)
    work.recursive = (tree_dynamics(chart, work.kin, derivation=not work.small,
                                    square_outputs=not work.large)
                      if dynamics != "dense" else None)
    if work.recursive is None and dynamics == "recursive":
        raise ModelError(
            "--dynamics recursive: the model is neither a tree of particles (each particle "
            "its parent's position plus an offset in coordinates of its own) nor a joint "
            "tree of bodies (links, URDF); use --dynamics auto or dense")
    work.tree_derived = work.recursive is not None and not work.small
    if work.small:
        work.derivation, work.definitions = derive(chart, work.kin), []
    elif work.tree_derived:
        assert work.recursive is not None  # tree_derived: the recursions give every output
        work.derivation, work.definitions = work.recursive.derivation, []
    else:
        work.derivation, work.definitions = derive_structured(chart, work.kin)
    if work.recursive:
        work.definitions = [*work.definitions, *work.recursive.definitions]
    # a body's rods and pins make symbolic derivatives of the penalty forces slow (seconds
    # for one top); forward mode after CSE gives the same values
    symbolic = work.small and not chart.bodies
    assert work.derivation is not None  # set above
    work.derivation.constraints = work.constraints
    if work.options.maximal and has_maximal_model(chart):
        work.maximal = derive_maximal(chart, symbolic_jacobians=symbolic, named=not symbolic)
        work.definitions = [*work.definitions, *work.maximal.definitions]


def _optimize(work: _ChartWork, name: str) -> GeneratedChart:
    chart, options = work.chart, work.options
    derivation, maximal = work.derivation, work.maximal
    assert derivation is not None  # set by _derive
    looped = None
    if work.tree_derived and work.large:
        assert work.recursive is not None  # tree_derived: the recursions give every output
        looped = looped_outputs(derivation, work.recursive.residual)
    part_statements = options.part_statements_for(looped is not None)
    optimize_options = OptimizeOptions(part_statements, always_parts=options.translation_units > 0,
                                       zero_fill_min=options.zero_fill_min)
    kernels = build_kernels(derivation, work.recursive, work.tree_derived, looped)
    maximal_kernels = build_maximal_kernels(maximal) if maximal else []
    names, input_of = _symbol_names(chart)
    if looped:
        names.update(looped.names)
        input_of.update(looped.input_of)
    optimized = optimize_model(derivation, kernels + maximal_kernels, names, input_of,
                               work.definitions, optimize_options)
    optimized.kernels, paths = choose_paths(optimized.kernels, chart.nq, options.dynamics,
                                            work.tree_derived)
    analysis = work.analysis + paths.report
    if looped:
        analysis.append(f"Mt, J, dr/dq and dr/dv: loops over their columns, each an O(nq) "
                        f"product (nq = {chart.nq}, from --loop-min-nq {options.loop_min_nq} "
                        f"on); kernels cut into parts of at most {part_statements} statements")
    reduced = len(optimized.kernels) - len(maximal_kernels)
    no_maximal = "" if maximal else (
        why_no_maximal_model(chart) if options.maximal else
        "generated without --maximal (gencoord crosscheck generates with it)")
    return GeneratedChart(chart, chart_name(name, work.model, chart), optimized, reduced,
                          maximal, analysis, work.conservative, work.dissipative, paths,
                          no_maximal or "")


def _generate_chart(path: str, model: Model, chart: Model, name: str, options: GenerateOptions,
                    observers: _Observers) -> GeneratedChart:
    prefix = f"chart {chart.chart}: " if model.charts else ""
    try:
        work = _ChartWork(model, chart, options, Kinematics(chart))
        # X, J and xdot of every point (work.kin) are shared by the stages below
        for label, stage in (("check", _check), ("analyse", _analyse), ("derive", _derive)):
            stage(work, observers)
            observers.stage_done(prefix + label)
        generated = _optimize(work, name)
    except ModelError as error:
        raise error.located(path, None) from None
    observers.stage_done(prefix + "optimize (CSE)")
    return generated


def _analysis_lines(model: Model, charts: list[GeneratedChart]) -> list[str]:
    """Every chart's analysis, under a heading per chart for an atlas."""
    return [line for chart in charts for line in (
        ([f"Chart '{chart.model.chart}' ({chart.name}):"] if model.charts else [])
        + [("  " if model.charts else "") + text for text in chart.analysis])]


def _emit(path: str, model: Model, name: str, docstring: str, charts: list[GeneratedChart],
          options: GenerateOptions, output_flags: Sequence[str]) -> Generated:
    analysis = _analysis_lines(model, charts)
    units = options.translation_units
    if units:
        parts = [(part, is_derivative_path(kernel.kernel.name)) for chart in charts
                 for kernel in chart.optimized.kernels for part in kernel.parts]
        groups = assign_role_groups([len(part.lines) for part, _ in parts],
                                    [on_path for _, on_path in parts], units)
        for (part, _), group in zip(parts, groups):
            part.group = group
    flags = options.banner_flags() + list(output_flags)
    source_path = shell_word(working_directory_relative(path))
    header = render_model(charts, name, docstring, source_path, f"generated/{name}.hpp",
                          analysis, flags, units, options.unroll_max_nq)
    sources = {instantiation_file_name(name, group): render_instantiation(
                   charts, name, source_path, flags, group, units)
               for group in range(units)}
    return Generated(name, header, analysis, [], sources, scene_json(model, name))


def generate(path: str, model_options: dict[str, str] | None = None,
             options: GenerateOptions = GenerateOptions(), *,
             on_stage: Callable[[str, float], None] | None = None,
             on_warning: Callable[[str], None] | None = None,
             output_flags: Sequence[str] = ()) -> Generated:
    """Runs every stage for one model file (each chart of an atlas) with the build options
    `model_options` (`--set n=5`); raises ModelError. `on_stage` hears each stage's time,
    `on_warning` of a generation expected to take minutes or more; `output_flags` (an -o DIR
    that is not the default) end the banner's regenerate command."""
    observers = _Observers(on_stage, on_warning)
    model, name, docstring = load_model(path, model_options, options.name, options.load_timeout)
    observers.stage_done("load")
    try:
        check_atlas(model)
    except ModelError as error:
        raise error.located(path, None) from None
    charts = [_generate_chart(path, model, chart, name, options, observers)
              for chart in [model, *model.charts]]
    generated = _emit(path, model, name, docstring, charts, options, output_flags)
    observers.stage_done("emit")
    generated.timings = observers.timings
    return generated
