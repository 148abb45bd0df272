"""The stages of one generation, each timed: load, check, derive, optimize, emit."""

from __future__ import annotations

import os
import shlex
import time
from dataclasses import dataclass, field
from typing import Callable, Sequence

from .atlas import check_atlas
from .body_tree import body_tree
from .conservative import forces_have_potential
from .constraints import verify_constraints
from .derive import Kinematics, derive
from .dynamics_paths import PathChoice, choose_paths
from .errors import ModelError
from .emit import instantiation_file_name, render_instantiation, render_model
from .kernels import build_kernels, build_maximal_kernels
from .limits import LOAD_TIMEOUT, size_warning
from .loader import load_model
from .looped import LOOP_MIN_NQ, looped_outputs
from .maximal import KAPPA, PENALTY_DAMPING, derive_maximal
from .model import Model
from .naming import chart_name
from .optimize import OptimizeOptions, optimize_model
from .rank import check_full_rank
from .scene import scene_json
from .singularities import analyse_singularities
from .split import assign_groups, default_part_statements
from .structured import derive_structured
from .tree_dynamics import tree_dynamics
from .validate import validate


# Up to this many coordinates every output is one flat expression (derive.py), which lets
# SymPy cancel terms exactly (pendulum_3d's Fi is 0) and differentiate the maximal forces
# symbolically; larger models use named intermediates (structured.py) and forward-mode
# Jacobians, which scale to hundreds of coordinates.
FLAT_MAX_NQ = 3


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
        names[c.rate], input_of[c.rate] = c.rate.name, "v"
        names[c.acceleration], input_of[c.acceleration] = c.acceleration.name, "qdd"
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
    optimized: object
    num_reduced_kernels: int
    maximal: object
    analysis: list[str]
    forces_have_potential: bool          # conservative.py: the struct's forces_have_potential
    paths: PathChoice                    # dense or recursive qddot and inverse_dynamics


def generate(path: str, options: dict[str, str] | None = None,
             on_stage: Callable[[str, float], None] | None = None,
             max_part_statements: int | None = None,
             translation_units: int = 0, dynamics: str = "auto",
             regenerate_options: Sequence[str] = (), name: str | None = None,
             load_timeout: float | None = LOAD_TIMEOUT,
             on_warning: Callable[[str], None] | None = None,
             loop_min_nq: int = LOOP_MIN_NQ) -> Generated:
    """Runs every stage for one model file (each chart of an atlas); raises ModelError.

    Kernels of more than `max_part_statements` statements are emitted in parts (split.py);
    0 never splits, None chooses by the model (split.default_part_statements). With
    `translation_units` N > 0 every kernel is parts, spread over N groups each compiled for
    double in a source file of its own, which the header declares
    `extern template`: the files compile in parallel, and code including the header compiles
    no kernel body for double. `dynamics` chooses the forward and inverse dynamics of a
    tree model (dynamics_paths.py): "auto", "dense" or "recursive" (an error for a model
    that is not a tree). `regenerate_options` (such as an -o DIR that is not the
    default) end the banner's regenerate command. `name` replaces the file's stem in the
    model's name (the header's and the C++ type's); the model file may run `load_timeout`
    seconds. `on_warning` hears of a generation expected to take minutes or more. A tree
    of `loop_min_nq` coordinates or more gets its Mt, J and residual Jacobians as loops over
    O(n) products (looped.py).
    """
    timings: list[tuple[str, float]] = []

    def stage(label: str, start: float) -> float:
        now = time.perf_counter()
        timings.append((label, now - start))
        if on_stage:
            on_stage(label, now - start)
        return now

    start = time.perf_counter()
    model, name, docstring = load_model(path, options, name, load_timeout)
    start = stage("load", start)
    try:
        check_atlas(model)
    except ModelError as error:
        raise error.located(path, None) from None
    charts = []
    for chart in [model, *model.charts]:
        prefix = f"chart {chart.chart}: " if model.charts else ""
        try:
            validate(chart)
            kin = Kinematics(chart)  # X, J and xdot of every point, shared by the stages below
            if chart is model:
                tree = kin.tree is not None or body_tree(model) is not None
                warning = size_warning(model, tree)
                if warning and on_warning:
                    on_warning(warning)
            notes = check_full_rank(chart, kin=kin) + verify_constraints(chart, kin=kin)
        except ModelError as error:
            raise error.located(path, None) from None
        start = stage(prefix + "check", start)
        analysis = analyse_singularities(chart, kin=kin).lines() + notes
        conservative = forces_have_potential(chart, kin)
        start = stage(prefix + "analyse", start)
        small = chart.nq <= FLAT_MAX_NQ
        # a large tree's n^2 outputs are loops over its recursions' products (looped.py)
        large = chart.nq >= loop_min_nq
        # --dynamics dense: the dense derivation and kernels, the reference
        recursive = (tree_dynamics(chart, kin, derivation=not small, square_outputs=not large)
                     if dynamics != "dense" else None)
        if recursive is None and dynamics == "recursive":
            raise ModelError(
                "--dynamics recursive: the model is neither a tree of particles (each particle "
                "its parent's position plus an offset in coordinates of its own) nor a joint "
                "tree of bodies (links, URDF); use --dynamics auto or dense"
            ).located(path, None)
        # a large tree's every output comes from its recursions, in O(n) intermediates
        tree_derived = recursive is not None and not small
        if small:
            derivation, definitions = derive(chart, kin), []
        elif tree_derived:
            derivation, definitions = recursive.derivation, []
        else:
            derivation, definitions = derive_structured(chart, kin)
        if recursive:
            definitions = [*definitions, *recursive.definitions]
        # a body's rods and pins make symbolic derivatives of the penalty forces slow (seconds
        # for one top); forward mode after CSE gives the same values
        symbolic = small and not chart.bodies
        maximal = derive_maximal(chart, symbolic_jacobians=symbolic, named=not symbolic)
        definitions = [*definitions, *maximal.definitions]
        start = stage(prefix + "derive", start)
        looped = looped_outputs(derivation, recursive.residual) if tree_derived and large else None
        part_statements = (max_part_statements if max_part_statements is not None
                           else default_part_statements(looped is not None))
        optimize_options = OptimizeOptions(part_statements, always_parts=translation_units > 0)
        kernels = build_kernels(derivation, recursive, tree_derived, looped)
        maximal_kernels = build_maximal_kernels(maximal)
        names, input_of = _symbol_names(chart)
        if looped:
            names.update(looped.names)
            input_of.update(looped.input_of)
        optimized = optimize_model(derivation, kernels + maximal_kernels, names, input_of,
                                   definitions, optimize_options)
        optimized.kernels, paths = choose_paths(optimized.kernels, chart.nq, dynamics,
                                                tree_derived)
        analysis += paths.report
        if looped:
            analysis.append(f"Mt, J, dr/dq and dr/dv: loops over their columns, each an O(nq) "
                            f"product (nq = {chart.nq}, from --loop-min-nq {loop_min_nq} on); "
                            f"kernels cut into parts of at most {part_statements} statements")
        start = stage(prefix + "optimize (CSE)", start)
        reduced = len(optimized.kernels) - len(maximal_kernels)
        charts.append(GeneratedChart(chart, chart_name(name, model, chart), optimized,
                                     reduced, maximal, analysis, conservative, paths))
    analysis = [line for chart in charts for line in (
        ([f"Chart '{chart.model.chart}' ({chart.name}):"] if model.charts else [])
        + [("  " if model.charts else "") + text for text in chart.analysis])]
    flags = ([f"--max-function-statements {max_part_statements}"]
             if max_part_statements is not None else [])
    if loop_min_nq != LOOP_MIN_NQ:
        flags.append(f"--loop-min-nq {loop_min_nq}")
    if translation_units:
        flags.append(f"--translation-units {translation_units}")
        parts = [part for chart in charts for kernel in chart.optimized.kernels
                 for part in kernel.parts]
        for part, group in zip(parts, assign_groups([len(p.lines) for p in parts],
                                                    translation_units)):
            part.group = group
    flags += list(regenerate_options)
    source_path = shlex.quote(working_directory_relative(path))
    header = render_model(charts, name, docstring, source_path, f"generated/{name}.hpp",
                          analysis, flags, translation_units)
    sources = {instantiation_file_name(name, group): render_instantiation(
                   charts, name, source_path, flags, group, translation_units)
               for group in range(translation_units)}
    scene = scene_json(model, name)
    stage("emit", start)
    return Generated(name, header, analysis, timings, sources, scene)
