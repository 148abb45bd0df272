# SPDX-License-Identifier: BSD-3-Clause
"""The sweep file's content, checked: which model, how to integrate, the event, the samples
and what to record (docs/sweep.md describes each key). `parse()` checks the file's form;
`check_names()` then checks the names in it against the loaded model."""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, replace
from typing import NoReturn

from gencoord.sweep import event as event_module
from gencoord.sweep.numbers import NotANumber, parse_number
from gencoord.sweep.source import Key, SweepSource

INTEGRATORS = ("forward_euler", "symplectic_euler", "rk4", "backward_euler", "trapezoidal",
               "implicit_midpoint")
METHODS = ("grid", "latin_hypercube", "monte_carlo")
KINDS = ("q", "v", "parameters")  # what a sampled variable sets, in the order they vary
MAX_SAMPLES = 100_000_000
MAX_STEPS = 10**9  # steps of one sample
MAX_SEED = 2**63 - 1  # the result file holds the seed as a signed 64-bit integer
DEFAULT_CHUNK = 256
ERROR_BYTES = 64  # a sample's error text, as the program stores it
MPI_MESSAGE_BYTES = 2**31 - 1  # MPI counts a message's bytes in an int

_SCHEMA = {
    "model": ("file", "options", "parameters"),
    "integration": ("integrator", "dt", "t_end"),
    "event": ("when", "stop"),
    "initial": ("q", "v"),
    "samples": ("method", "count", "seed", "chunk", *KINDS),
    "record": ("final_state", "energy_drift", "event_time", "trajectory_every"),
}


@dataclass(frozen=True)
class Variable:
    """A sampled quantity: `kind` (q, v or parameters) and `name`; for a grid its `values`,
    for a random method the interval [low, high)."""
    kind: str
    name: str
    key: Key
    values: tuple[float, ...] = ()
    low: float = 0.0
    high: float = 0.0

    @property
    def label(self) -> str:
        return f"{self.kind}.{self.name}"


@dataclass(frozen=True)
class Record:
    final_state: bool
    energy_drift: bool
    event_time: bool
    trajectory_every: int  # 0: no trajectory


@dataclass(frozen=True)
class Event:
    text: str
    clauses: tuple[event_module.Clause, ...]
    stop: bool


@dataclass(frozen=True)
class Sweep:
    source: SweepSource
    name: str                     # the file's stem: names the output files
    model_file: str               # absolute
    options: dict[str, str]       # build options
    parameters: dict[str, float]  # parameter values of every sample (before sampled ones)
    integrator: str
    dt: float
    t_end: float
    steps: int
    event: Event | None
    initial: dict[str, dict[str, float]]  # "q" and "v": coordinate -> value
    method: str
    count: int                    # samples
    seed: int | None
    chunk: int
    variables: tuple[Variable, ...]
    record: Record


class _Reader:
    """Typed access to the TOML data; every failure is a located SweepFileError."""

    def __init__(self, source: SweepSource):
        self.source = source

    def fail(self, key: Key, message: str) -> NoReturn:
        raise self.source.error(key, message)

    def table(self, key: Key, value, allowed: tuple[str, ...] | None) -> dict:
        if not isinstance(value, dict):
            self.fail(key, f"expects a table, got {value!r}")
        if allowed is not None:
            for name in value:
                if name not in allowed:
                    self.fail(key + (name,), f"unknown key; {key[-1] if key else 'the file'} "
                                             f"takes {', '.join(allowed)}")
        return value

    def number(self, key: Key, value) -> float:
        try:
            return parse_number(value)
        except NotANumber as error:
            self.fail(key, str(error))

    def integer(self, key: Key, value, minimum: int) -> int:
        if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
            self.fail(key, f"expects a whole number >= {minimum}, got {value!r}")
        return value

    def boolean(self, key: Key, value) -> bool:
        if not isinstance(value, bool):
            self.fail(key, f"expects true or false, got {value!r}")
        return value

    def string(self, key: Key, value, choices: tuple[str, ...] | None = None) -> str:
        if not isinstance(value, str) or (choices and value not in choices):
            expected = f"one of {', '.join(choices)}" if choices else "a string"
            self.fail(key, f"expects {expected}, got {value!r}")
        return value

    def required(self, data: dict, key: Key):
        if key[-1] not in data:
            self.fail(key[:-1], f"needs '{key[-1]}' (docs/sweep.md lists every key)")
        return data[key[-1]]

    def numbers(self, key: Key, value) -> dict[str, float]:
        table = self.table(key, value, None)
        return {name: self.number(key + (name,), item) for name, item in table.items()}


def _steps(reader: _Reader, dt: float, t_end: float) -> int:
    if not dt > 0:
        reader.fail(("integration", "dt"), f"expects a positive step, got {dt!r}")
    if not t_end > 0:
        reader.fail(("integration", "t_end"), f"expects a positive end time, got {t_end!r}")
    ratio = t_end / dt  # inf where t_end is near the largest double and dt small
    if not ratio <= MAX_STEPS:
        reader.fail(("integration", "dt"),
                    f"dt = {dt!r} makes {ratio:.3g} steps of each sample to t_end = {t_end!r}, "
                    f"more than the {MAX_STEPS:.0e} a sweep allows (at tens of nanoseconds a "
                    "step, 10^9 steps are a minute of CPU per sample); raise dt or shorten "
                    "t_end")
    steps = round(ratio)
    if abs(steps * dt - t_end) > 1e-6 * dt:  # as the runtime's step_count() demands
        reader.fail(("integration", "t_end"),
                    f"t_end = {t_end!r} is not a whole number of steps of dt = {dt!r} "
                    f"(t_end / dt = {t_end / dt:.6g}); change one of them")
    return steps


def _variable(reader: _Reader, key: Key, spec, method: str) -> Variable:
    kind, name = key[-2], key[-1]
    if method == "grid":
        table = reader.table(key, spec, ("from", "to", "points", "values"))
        if "values" in table:
            if set(table) != {"values"}:
                reader.fail(key, "give either values = [...] or from, to and points")
            items = table["values"]
            if not isinstance(items, list) or not items:
                reader.fail(key + ("values",), "expects a non-empty list of numbers")
            values = tuple(reader.number(key + ("values",), v) for v in items)
            return Variable(kind, name, key, values=values)
        for part in ("from", "to", "points"):
            reader.required(table, key + (part,))
        low = reader.number(key + ("from",), table["from"])
        high = reader.number(key + ("to",), table["to"])
        points = reader.integer(key + ("points",), table["points"], 1)
        if points > MAX_SAMPLES:
            reader.fail(key + ("points",), f"{points} points is more than the {MAX_SAMPLES} "
                        "samples a sweep may have; split the sweep into several files")
        if points == 1:
            return Variable(kind, name, key, values=(low,))
        step = (high - low) / (points - 1)
        if not math.isfinite(step):
            reader.fail(key, f"the points from {low!r} to {high!r} are not finite numbers "
                        "(their spacing overflows); give a range of at most about 1e308")
        # numpy.linspace's points: low + k step, and the last one exactly `high`
        values = tuple(low + k * step for k in range(points - 1)) + (high,)
        return Variable(kind, name, key, values=values)
    table = reader.table(key, spec, ("from", "to"))
    for part in ("from", "to"):
        reader.required(table, key + (part,))
    low = reader.number(key + ("from",), table["from"])
    high = reader.number(key + ("to",), table["to"])
    if not high >= low:
        reader.fail(key + ("to",), f"expects to >= from, got from = {low!r}, to = {high!r}")
    if not math.isfinite(high - low):
        reader.fail(key, f"the range from {low!r} to {high!r} is wider than a double holds; "
                    "give a range of at most about 1e308")
    return Variable(kind, name, key, low=low, high=high)


def _samples(reader: _Reader, data: dict):
    key = ("samples",)
    table = reader.table(key, reader.required(data, key), _SCHEMA["samples"])
    method = reader.string(key + ("method",), reader.required(table, key + ("method",)),
                           METHODS)
    variables = []
    for kind in KINDS:
        group = reader.table(key + (kind,), table.get(kind, {}), None)
        for name, spec in group.items():
            variables.append(_variable(reader, key + (kind, name), spec, method))
    if not variables:
        reader.fail(key, "samples nothing: add a table such as [samples.q] with a variable")
    seed = None
    if method == "grid":
        for extra in ("count", "seed"):
            if extra in table:
                reader.fail(key + (extra,), "a grid has no count or seed; its points are "
                                            "given per variable")
        count = math.prod(len(v.values) for v in variables)
    else:
        count = reader.integer(key + ("count",), reader.required(table, key + ("count",)), 1)
        seed = reader.integer(key + ("seed",), reader.required(table, key + ("seed",)), 0)
        if seed > MAX_SEED:
            reader.fail(key + ("seed",), f"expects a seed of at most 2^63 - 1 = {MAX_SEED} "
                        f"(the result file records it as a 64-bit integer), got {seed}")
    if count > MAX_SAMPLES:
        reader.fail(key, f"{count} samples is more than {MAX_SAMPLES}; split the sweep into "
                         "several files")
    chunk = reader.integer(key + ("chunk",), table.get("chunk", DEFAULT_CHUNK), 1)
    return method, count, seed, min(chunk, count), tuple(variables)


def _event(reader: _Reader, data: dict) -> Event | None:
    if "event" not in data:
        return None
    key = ("event",)
    table = reader.table(key, data["event"], _SCHEMA["event"])
    text = reader.string(key + ("when",), reader.required(table, key + ("when",)))
    try:
        clauses = event_module.parse_condition(text)
    except event_module.EventSyntaxError as error:
        reader.fail(key + ("when",), str(error))
    stop = reader.boolean(key + ("stop",), table.get("stop", True))
    return Event(text=text, clauses=clauses, stop=stop)


def _record(reader: _Reader, data: dict, event: Event | None, steps: int) -> Record:
    key = ("record",)
    table = reader.table(key, data.get("record", {}), _SCHEMA["record"])
    flags = {name: reader.boolean(key + (name,), table.get(name, True))
             for name in ("final_state", "energy_drift")}
    event_time = reader.boolean(key + ("event_time",), table.get("event_time", bool(event)))
    if event_time and not event:
        reader.fail(key + ("event_time",), "there is no [event]; add one, or set it false")
    every = reader.integer(key + ("trajectory_every",), table.get("trajectory_every", 0), 0)
    if every > steps:
        reader.fail(key + ("trajectory_every",),
                    f"{every} steps is more than the run's {steps}; record every k-th step "
                    "with k <= t_end / dt")
    return Record(event_time=event_time, trajectory_every=every, **flags)


def parse(source: SweepSource) -> Sweep:
    """The sweep the file describes, its form checked (names are checked by check_names())."""
    reader = _Reader(source)
    data = reader.table((), source.data, tuple(_SCHEMA))
    model = reader.table(("model",), reader.required(data, ("model",)), _SCHEMA["model"])
    file = reader.string(("model", "file"), reader.required(model, ("model", "file")))
    folder = os.path.dirname(os.path.abspath(source.path))
    model_file = os.path.normpath(os.path.join(folder, os.path.expanduser(file)))
    if not os.path.isfile(model_file):
        reader.fail(("model", "file"), f"no such file {model_file} (a path relative to the "
                                       "sweep file's folder, or absolute)")
    options = {}
    for name, value in reader.table(("model", "options"), model.get("options", {}),
                                    None).items():
        if isinstance(value, (dict, list)):
            reader.fail(("model", "options", name), "expects a number, string or boolean")
        options[name] = str(value).lower() if isinstance(value, bool) else str(value)
    parameters = reader.numbers(("model", "parameters"), model.get("parameters", {}))

    integration = reader.table(("integration",), reader.required(data, ("integration",)),
                               _SCHEMA["integration"])
    integrator = reader.string(("integration", "integrator"),
                               integration.get("integrator", "rk4"), INTEGRATORS)
    dt = reader.number(("integration", "dt"),
                       reader.required(integration, ("integration", "dt")))
    t_end = reader.number(("integration", "t_end"),
                          reader.required(integration, ("integration", "t_end")))
    steps = _steps(reader, dt, t_end)

    initial_table = reader.table(("initial",), data.get("initial", {}), _SCHEMA["initial"])
    initial = {kind: reader.numbers(("initial", kind), initial_table.get(kind, {}))
               for kind in ("q", "v")}
    event = _event(reader, data)
    method, count, seed, chunk, variables = _samples(reader, data)
    record = _record(reader, data, event, steps)
    name = os.path.splitext(os.path.basename(source.path))[0]
    return Sweep(source=source, name=name, model_file=model_file, options=options,
                 parameters=parameters, integrator=integrator, dt=dt, t_end=t_end, steps=steps,
                 event=event, initial=initial, method=method, count=count, seed=seed,
                 chunk=chunk, variables=variables, record=record)


def check_names(sweep: Sweep, coordinates: list[str], parameters: list[str],
                speeds: list[str] | None = None) -> Sweep:
    """Checks every coordinate, velocity and parameter the sweep names against the model's;
    returns the sweep with its event's quantities resolved. `speeds` names v's entries, a
    model's generalized speeds (None: its coordinates, v = q')."""
    reader = _Reader(sweep.source)
    model_name = os.path.basename(sweep.model_file)

    def check(key: Key, name: str, known: list[str], what: str) -> None:
        if name not in known:
            reader.fail(key, f"{model_name} has no {what} '{name}' (it has "
                             f"{', '.join(known) or 'none'})")

    for name in sweep.parameters:
        check(("model", "parameters", name), name, parameters, "parameter")
    velocities = coordinates if speeds is None else speeds
    known = {"q": (coordinates, "coordinate"),
             "v": (velocities, "coordinate" if speeds is None else "speed"),
             "parameters": (parameters, "parameter")}
    for kind in ("q", "v"):
        for name in sweep.initial[kind]:
            check(("initial", kind, name), name, *known[kind])
    for variable in sweep.variables:
        check(variable.key, variable.name, *known[variable.kind])
    _check_chunk_bytes(reader, sweep, len(coordinates), len(velocities))
    if sweep.event is None:
        return sweep
    names = event_module.velocity_names(coordinates, speeds)
    try:
        clauses = tuple(event_module.resolve(c, coordinates, names) for c in sweep.event.clauses)
    except event_module.EventSyntaxError as error:
        reader.fail(("event", "when"), str(error))
    return replace(sweep, event=replace(sweep.event, clauses=clauses))


def trajectory_points(sweep: Sweep) -> int:
    """Recorded trajectory points of one sample: steps 0, every, 2 every, ... (0: none)."""
    every = sweep.record.trajectory_every
    return sweep.steps // every + 1 if every else 0


def result_bytes(sweep: Sweep, nq: int, nv: int | None = None) -> int:
    """One sample's results: status, error time and text, and what the file records (q has
    nq entries, v nv: nq where v = q')."""
    record = sweep.record
    state = 8 * (nq + (nq if nv is None else nv))
    return (1 + 8 + ERROR_BYTES + (8 + state if record.final_state else 0)
            + 8 * record.energy_drift + 8 * record.event_time
            + trajectory_points(sweep) * state)


def _check_chunk_bytes(reader: _Reader, sweep: Sweep, nq: int, nv: int) -> None:
    """A chunk travels between ranks as one MPI message, whose size is an int: its rows and its
    results must each stay under 2 GiB."""
    per_sample = max(result_bytes(sweep, nq, nv), 8 * len(sweep.variables))
    largest = (MPI_MESSAGE_BYTES - 64) // per_sample
    if sweep.chunk > largest:
        reader.fail(("samples", "chunk"),
                    f"a chunk of {sweep.chunk} samples is {sweep.chunk * per_sample} bytes of "
                    f"results, more than one MPI message holds; set chunk <= {largest}")
