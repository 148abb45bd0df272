"""The stages of one generation, each timed: load, check, derive, optimize, emit."""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, field
from typing import Callable

from .derive import derive
from .errors import ModelError
from .emit import render_model
from .kernels import build_kernels
from .loader import load_model
from .optimize import optimize
from .validate import validate


@dataclass
class Generated:
    name: str
    header: str                                   # the header's text
    timings: list[tuple[str, float]] = field(default_factory=list)


def _repository_relative(path: str) -> str:
    """A stable path for banners: relative to the repository when inside it."""
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    absolute = os.path.abspath(path)
    if absolute.startswith(root + os.sep):
        return os.path.relpath(absolute, root)
    return os.path.basename(absolute)


def generate(path: str, options: dict[str, str] | None = None,
             on_stage: Callable[[str, float], None] | None = None) -> Generated:
    """Runs every stage for one model file; raises ModelError on bad input."""
    timings: list[tuple[str, float]] = []

    def stage(label: str, start: float) -> float:
        now = time.perf_counter()
        timings.append((label, now - start))
        if on_stage:
            on_stage(label, now - start)
        return now

    start = time.perf_counter()
    model, name, docstring = load_model(path, options)
    start = stage("load", start)
    try:
        validate(model)
    except ModelError as error:
        raise error.located(path, None) from None
    start = stage("check", start)
    derivation = derive(model)
    start = stage("derive", start)
    kernels = build_kernels(derivation)
    names = {c.symbol: c.name for c in model.coordinates}
    names.update({c.rate: c.rate.name for c in model.coordinates})
    names.update({p.symbol: p.name for p in model.parameters})
    names[model.time] = "t"
    optimized = optimize(derivation, kernels, names)
    start = stage("optimize (CSE)", start)
    header = render_model(model, name, docstring, _repository_relative(path),
                          f"generated/{name}.hpp", optimized)
    stage("emit", start)
    return Generated(name, header, timings)
