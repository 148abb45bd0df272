# SPDX-License-Identifier: BSD-3-Clause
"""Draws a trajectory CSV as an SVG: particle paths and energy error. `gencoord simulate`
draws one after every run; by hand:

    python3 -m gencoord.tool.trajectory_svg out/double_pendulum.csv out/double_pendulum.svg \
        [--name NAME]

Standard library only. The left panel shows the particle paths in the two spatial axes along
which the points move the most (the plane of motion for planar models), in metres, at equal
aspect, with the model's fixed points (columns `fixed:<name>_x`, ...) marked; a fixed point
that moves (a driven pivot) also gets its path, drawn lighter. The right panel shows the
energy error relative to E(0) against time, or the absolute error in J when E(0) = 0.
The model name defaults to the CSV file's stem.
"""
from __future__ import annotations

import argparse
import csv
import math
import os
from dataclasses import dataclass
from xml.sax.saxutils import quoteattr

from gencoord.tool.csv_columns import parse_columns, read_columns
from gencoord.tool.errors import ToolError
from gencoord.tool.svg_plot import (COLOURS, Frame, TICK_TARGET, axes, decade_of, element, envelope,
                                    key_width, legend_key, nice_step, padded_range, polyline,
                                    scaled_label, ticks_within, time_axis)

WIDTH, HEIGHT = 1000, 540
PATH_RECT = (80, 70, 380, 380)      # left, top, width, height (square: equal aspect)
ENERGY_RECT = (600, 70, 370, 380)
FIXED_COLOUR = "#222222"
FIXED_PREFIX = "fixed:"              # csv_writer.hpp's prefix of fixed-point columns


# --- reading -----------------------------------------------------------------------------

@dataclass
class Trajectory:
    """One CSV's columns, with the points it holds sorted into particles and fixed points."""
    columns: dict[str, list[float]]
    particles: list[str]
    fixed_points: list[str]
    axes: list[str]                  # "x", "y" and, in 3D, "z"

    @property
    def t(self) -> list[float]:
        return self.columns["t"]

    @property
    def energy(self) -> list[float]:
        return self.columns["energy"]

    @property
    def work(self) -> list[float] | None:
        """W(t), the work of a dissipative model's dampers and friction (csv_writer.hpp)."""
        return self.columns.get("work")

    def path(self, point: str, axis: str) -> list[float]:
        """The coordinate `axis` of a particle or fixed point over time."""
        return self.columns[f"{point}_{axis}"]


def parse_trajectory(lines, path: str = "the CSV") -> Trajectory:
    """Reads CSV text (an iterable of lines) in csv_writer.hpp's layout; a ToolError naming
    `path` and the line for anything else."""
    try:
        columns = parse_columns(csv.reader(lines, skipinitialspace=True), path)
    except csv.Error as error:
        raise ToolError(f"{path}: not a CSV file ({error})") from None
    return _trajectory(columns, path)


def read_trajectory(path: str) -> Trajectory:
    return _trajectory(read_columns(path), path)


def _trajectory(columns: dict[str, list[float]], path: str) -> Trajectory:
    header = list(columns)
    if "energy" not in columns:
        raise ToolError(f"{path}: no column 'energy'; expected a trajectory of gencoord "
                        "simulate (t, q_..., v_..., energy, positions)")
    point_columns = [name for name in header if not name.startswith(("q_", "v_", "limit:"))
                     and name.rsplit("_", 1)[-1] in ("x", "y", "z") and "_" in name]
    points = list(dict.fromkeys(name.rsplit("_", 1)[0] for name in point_columns))
    if not points:
        raise ToolError(f"{path}: no position columns (<particle>_x, <particle>_y, ...); "
                        "expected a trajectory of gencoord simulate")
    axes = ["x", "y"] + (["z"] if f"{points[0]}_z" in columns else [])
    for point in points:
        missing = [f"{point}_{a}" for a in axes if f"{point}_{a}" not in columns]
        if missing:
            raise ToolError(f"{path}: no column {missing[0]!r}: every point needs its "
                            f"{', '.join(axes)} columns")
    return Trajectory(columns=columns,
                      particles=[p for p in points if not p.startswith(FIXED_PREFIX)],
                      fixed_points=[p for p in points if p.startswith(FIXED_PREFIX)],
                      axes=axes)


def display_name(point: str) -> str:
    return point[len(FIXED_PREFIX):] if point.startswith(FIXED_PREFIX) else point


def is_moving(trajectory: Trajectory, point: str) -> bool:
    return any(max(trajectory.path(point, a)) > min(trajectory.path(point, a))
               for a in trajectory.axes)


# --- the particle-path panel -------------------------------------------------------------

def plane_of_motion(trajectory: Trajectory) -> tuple[str, str]:
    """The two axes along which the points spread the most, in x, y, z order."""
    if len(trajectory.axes) == 2:
        return trajectory.axes[0], trajectory.axes[1]
    points = trajectory.particles + trajectory.fixed_points
    spread = {a: sum(max(trajectory.path(p, a)) - min(trajectory.path(p, a)) for p in points)
              for a in trajectory.axes}
    first, second = sorted(sorted(trajectory.axes, key=lambda a: -spread[a])[:2])
    return first, second


def equal_aspect_frame(xs: list[float], ys: list[float], rect) -> tuple[Frame, float]:
    """A frame around all (xs, ys) with one metre as long on both axes, and its tick step."""
    x_lo, x_hi = padded_range(xs)
    y_lo, y_hi = padded_range(ys)
    _, _, width, height = rect
    metres_per_pixel = max((x_hi - x_lo) / width, (y_hi - y_lo) / height)
    x_mid, y_mid = (x_lo + x_hi) / 2, (y_lo + y_hi) / 2
    half_w, half_h = metres_per_pixel * width / 2, metres_per_pixel * height / 2
    frame = Frame((x_mid - half_w, x_mid + half_w, y_mid - half_h, y_mid + half_h), rect)
    return frame, nice_step(2 * max(half_w, half_h))


def fixed_point_marker(frame: Frame, name: str, x: float, y: float) -> list[str]:
    """A pivot symbol: a ring with a dot, and the point's name beside it."""
    px, py = frame.px(x), frame.py(y)
    return [element("circle", class_="fixed-point-marker", cx=f"{px:.1f}", cy=f"{py:.1f}",
                    r=6, fill="white", stroke=FIXED_COLOUR, stroke_width=2),
            element("circle", cx=f"{px:.1f}", cy=f"{py:.1f}", r=2, fill=FIXED_COLOUR),
            element("text", name, x=f"{px + 9:.1f}", y=f"{py - 8:.1f}", fill=FIXED_COLOUR,
                    font_size=12)]


def path_panel(trajectory: Trajectory) -> list[str]:
    ax, ay = plane_of_motion(trajectory)
    points = trajectory.particles + trajectory.fixed_points
    xs = [v for p in points for v in trajectory.path(p, ax)]
    ys = [v for p in points for v in trajectory.path(p, ay)]
    frame, step = equal_aspect_frame(xs, ys, PATH_RECT)
    x0, x1, y0, y1 = frame.bounds
    parts = ['<g id="path-panel">',
             *axes(frame, ticks_within(x0, x1, step), ticks_within(y0, y1, step),
                   f"{ax} (m)", f"{ay} (m)")]
    for k, particle in enumerate(trajectory.particles):
        colour = COLOURS[k % len(COLOURS)]
        px, py = trajectory.path(particle, ax), trajectory.path(particle, ay)
        parts += [f'<g class="particle" data-name={quoteattr(particle)}>',
                  polyline(frame, px, py, colour),
                  element("circle", cx=f"{frame.px(px[-1]):.1f}", cy=f"{frame.py(py[-1]):.1f}",
                          r=4, fill=colour),
                  "</g>"]
    for point in trajectory.fixed_points:
        name = display_name(point)
        px, py = trajectory.path(point, ax), trajectory.path(point, ay)
        parts.append(f'<g class="fixed-point" data-name={quoteattr(name)}>')
        if is_moving(trajectory, point):
            parts.append(polyline(frame, px, py, FIXED_COLOUR, stroke_opacity=0.35,
                                  class_="fixed-point-path"))
        parts += [*fixed_point_marker(frame, name, px[-1], py[-1]), "</g>"]
    parts += [*legend(trajectory), "</g>"]
    return parts


def legend(trajectory: Trajectory) -> list[str]:
    """One line under the path panel: each particle in its colour, then the fixed points."""
    left, top, _, height = PATH_RECT
    x: float  # advances by each key's width
    y, x, parts = top + height + 72, left - 60, ['<g class="legend">']
    for k, particle in enumerate(trajectory.particles):
        parts += legend_key(x, y, COLOURS[k % len(COLOURS)], particle)
        x += key_width(particle)
    for point in trajectory.fixed_points:
        label = display_name(point) + (" (moving fixed point)" if is_moving(trajectory, point)
                                       else " (fixed point)")
        parts += [element("circle", cx=x + 8, cy=y - 4, r=5, fill="white", stroke=FIXED_COLOUR,
                          stroke_width=2),
                  element("text", label, x=x + 20, y=y, fill=FIXED_COLOUR)]
        x += key_width(label)
    return parts + ["</g>"]


# --- the energy panel --------------------------------------------------------------------

@dataclass
class EnergyError:
    values: list[float]
    relative: bool                   # (E - E0) / |E0|; else E - E0 in J, because E0 = 0
    label: str
    name: str = "energy error"       # "energy change" for a model that does not conserve E
    # W(t), scaled as `values`, for a model whose energy changes by its dampers' and
    # friction's work alone: E - E0 should follow it, and the gap is the integrator's error
    work: list[float] | None = None

    @property
    def worst(self) -> float:
        return max(abs(v) for v in self.values)

    @property
    def balance(self) -> float:
        """max |E - E0 - W|, scaled as `values` (0 without W)."""
        return max((abs(e - w) for e, w in zip(self.values, self.work or [])), default=0.0)

    def summary(self) -> str:
        """The figure a run is judged by: the energy error, or the energy balance's."""
        gap = "E \u2212 E\u2080 \u2212 W" if self.work is not None else "E \u2212 E\u2080"
        value = self.balance if self.work is not None else self.worst
        text = (f"max |{gap}| / |E\u2080| = {value:.2e}" if self.relative
                else f"max |{gap}| = {value:.2e} J (E\u2080 = 0)")
        return text + (", W the dampers' and friction's work" if self.work is not None else "")


def energy_error(energy: list[float], conserved: bool = True,
                 work: list[float] | None = None) -> EnergyError:
    """E(t) against E(0): relative when E(0) != 0, else absolute in J. An error where the model
    conserves energy; its change where damping, inputs, time or joint limits change it, with
    `work`, W(t) of a dissipative model's dampers and friction, scaled alike."""
    e0, name = energy[0], "energy error" if conserved else "energy change"
    scale = abs(e0) if e0 != 0 else 1.0
    with_work = " and W" if work is not None else ""
    scaled_work = [w / scale for w in work] if work is not None else None
    if e0 != 0:
        return EnergyError([(e - e0) / scale for e in energy], True,
                           f"relative {name} (E \u2212 E\u2080){with_work} / |E\u2080|", name,
                           scaled_work)
    return EnergyError([e - e0 for e in energy], False,
                       f"{name} E \u2212 E\u2080{with_work} (J), absolute: E\u2080 = 0", name,
                       scaled_work)


def error_axis(values: list[float]) -> tuple[float, float, float]:
    """Bounds (lo, hi) that end on ticks around all `values`, and the tick step."""
    lo, hi = min(values), max(values)
    if hi == lo:
        lo, hi = lo - max(abs(lo), 1e-16), hi + max(abs(hi), 1e-16)
    step = nice_step(hi - lo, TICK_TARGET - 1)
    return math.floor(lo / step + 1e-9) * step, math.ceil(hi / step - 1e-9) * step, step


def energy_panel(trajectory: Trajectory, error: EnergyError) -> list[str]:
    t = trajectory.t
    t0, t1, t_ticks = time_axis(t)
    lo, hi, step = error_axis([*error.values, *(error.work or [])])
    frame = Frame((t0, t1, lo, hi), ENERGY_RECT)
    y_ticks = ticks_within(lo, hi, step)
    scale = decade_of(y_ticks)
    xs, ys = envelope(t, error.values)
    work = []
    if error.work is not None:  # dashed over E - E0, which it should follow
        wx, wy = envelope(t, error.work)
        work = [polyline(frame, wx, wy, "#d62728", class_="work", stroke_dasharray="6 4")]
    return ['<g id="energy-panel">',
            *axes(frame, t_ticks, y_ticks, "t (s)", scaled_label(error.label, scale),
                  y_scale=scale),
            element("line", x1=ENERGY_RECT[0], y1=f"{frame.py(0):.1f}",
                    x2=ENERGY_RECT[0] + ENERGY_RECT[2], y2=f"{frame.py(0):.1f}",
                    stroke="#999", stroke_dasharray="4 3"),
            polyline(frame, xs, ys, "#333", class_="energy-error"), *work,
            "</g>"]


# --- the picture -------------------------------------------------------------------------

def render_svg(trajectory: Trajectory, name: str, conserved: bool = True) -> str:
    """The whole picture as SVG text; `conserved`: whether the model conserves energy (its
    panel then shows the energy error, else the energy's change)."""
    error = energy_error(trajectory.energy, conserved, trajectory.work)
    ax, ay = plane_of_motion(trajectory)
    worst = error.summary()
    t = trajectory.t
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" '
             f'viewBox="0 0 {WIDTH} {HEIGHT}" font-family="sans-serif" font-size="13">',
             element("rect", width="100%", height="100%", fill="white"),
             element("text", f"{name}: particle paths in the {ax}{ay} plane", class_="title",
                     x=PATH_RECT[0] - 60, y=28, font_size=15, font_weight="bold"),
             element("text", f"{len(t)} states, t = {t[0]:g} \u2026 {t[-1]:g} s",
                     x=PATH_RECT[0] - 60, y=48, fill="#555"),
             element("text", f"{name}: {error.name}", class_="title", x=ENERGY_RECT[0] - 80,
                     y=28, font_size=15, font_weight="bold"),
             element("text", worst, class_="max-error", x=ENERGY_RECT[0] - 80, y=48,
                     fill="#555"),
             *path_panel(trajectory), *energy_panel(trajectory, error), "</svg>"]
    return "\n".join(parts) + "\n"


def write_svg(source: str, target: str, name: str | None = None, conserved: bool = True) -> None:
    """Draws the trajectory CSV `source` into `target`; `name` defaults to the CSV's stem;
    `conserved` as render_svg's."""
    name = name or os.path.splitext(os.path.basename(source))[0]
    svg = render_svg(read_trajectory(source), name, conserved)
    with open(target, "w", encoding="utf-8") as handle:
        handle.write(svg)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("source", help="trajectory CSV written by simulate")
    parser.add_argument("target", help="SVG file to write")
    parser.add_argument("--name", help="model name for the titles (default: the CSV's stem)")
    args = parser.parse_args(argv)
    write_svg(args.source, args.target, args.name)
    print(f"picture     {args.target}")


if __name__ == "__main__":
    main()
