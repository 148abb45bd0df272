"""Draws a trajectory CSV as an SVG: particle paths and energy error. `gencoord simulate`
draws one after every run; by hand:

    python3 -m tool.trajectory_svg out/double_pendulum.csv out/double_pendulum.svg [--name NAME]

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
from xml.sax.saxutils import escape, quoteattr

WIDTH, HEIGHT = 1000, 540
PATH_RECT = (80, 70, 380, 380)      # left, top, width, height (square: equal aspect)
ENERGY_RECT = (600, 70, 370, 380)
COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2"]
FIXED_COLOUR = "#222222"
FIXED_PREFIX = "fixed:"              # csv_writer.hpp's prefix of fixed-point columns
MAX_POLYLINE_POINTS = 2000           # keeps the file small; more is invisible at this size
TICK_TARGET = 6                      # about this many ticks per axis
SUPERSCRIPTS = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


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

    def path(self, point: str, axis: str) -> list[float]:
        """The coordinate `axis` of a particle or fixed point over time."""
        return self.columns[f"{point}_{axis}"]


def parse_trajectory(lines) -> Trajectory:
    """Reads CSV text (an iterable of lines) in csv_writer.hpp's layout."""
    rows = list(csv.reader(lines))
    header = rows[0]
    values = list(zip(*[[float(x) for x in row] for row in rows[1:] if row]))
    columns = dict(zip(header, (list(v) for v in values)))
    point_columns = [name for name in header if not name.startswith(("q_", "v_"))
                     and name.rsplit("_", 1)[-1] in ("x", "y", "z") and "_" in name]
    points = list(dict.fromkeys(name.rsplit("_", 1)[0] for name in point_columns))
    axes = [a for a in "xyz" if f"{points[0]}_{a}" in columns]
    return Trajectory(columns=columns,
                      particles=[p for p in points if not p.startswith(FIXED_PREFIX)],
                      fixed_points=[p for p in points if p.startswith(FIXED_PREFIX)],
                      axes=axes)


def read_trajectory(path: str) -> Trajectory:
    with open(path, newline="") as handle:
        return parse_trajectory(handle)


def display_name(point: str) -> str:
    return point[len(FIXED_PREFIX):] if point.startswith(FIXED_PREFIX) else point


def is_moving(trajectory: Trajectory, point: str) -> bool:
    return any(max(trajectory.path(point, a)) > min(trajectory.path(point, a))
               for a in trajectory.axes)


# --- ticks -------------------------------------------------------------------------------

def nice_step(span: float, target: int = TICK_TARGET) -> float:
    """The 1-2-5 step (times a power of ten) that cuts `span` into nearest `target` pieces."""
    power = 10.0 ** math.floor(math.log10(span / max(target, 1)))
    candidates = [mantissa * power for mantissa in (1.0, 2.0, 5.0, 10.0)]
    return min(candidates, key=lambda step: abs(math.log(span / step / target)))


def ticks_within(lo: float, hi: float, step: float) -> list[float]:
    """The multiples of `step` in [lo, hi], rounded so that they print cleanly."""
    first, last = math.ceil(lo / step - 1e-9), math.floor(hi / step + 1e-9)
    decimals = tick_decimals(step)
    return [round(k * step, decimals + 1) for k in range(first, last + 1)]


def tick_decimals(step: float) -> int:
    """Digits after the point that tell ticks `step` apart (steps are 1, 2 or 5 x 10^k)."""
    return max(0, -math.floor(math.log10(step) + 1e-9))


def format_tick(value: float, step: float) -> str:
    text = f"{value:.{tick_decimals(step)}f}"
    return "0" if float(text) == 0 else text.replace("-", "\u2212")


def time_axis(t: list[float]) -> tuple[float, float, list[float]]:
    """Bounds t[0] .. t[-1] of a time axis (one second long when they are equal) and its ticks."""
    if t[-1] > t[0]:
        return t[0], t[-1], ticks_within(t[0], t[-1], nice_step(t[-1] - t[0]))
    return t[0], t[0] + 1.0, ticks_within(t[0], t[0] + 1.0, nice_step(1.0))


def padded_range(values: list[float], fraction: float = 0.05) -> tuple[float, float]:
    """[min, max] of `values` widened by `fraction` of the span (by 1 when all are equal)."""
    lo, hi = min(values), max(values)
    pad = (hi - lo) * fraction if hi > lo else max(abs(lo), 1.0) * 0.5
    return lo - pad, hi + pad


def decade_of(values: list[float]) -> int:
    """The power of ten to factor out of tick labels: 0 for ordinary magnitudes."""
    largest = max((abs(v) for v in values), default=0.0)
    if largest == 0 or 1e-3 <= largest < 1e4:
        return 0
    return math.floor(math.log10(largest))


# --- drawing -----------------------------------------------------------------------------

@dataclass
class Frame:
    """Maps data bounds (x0, x1, y0, y1) onto a pixel rectangle (left, top, width, height)."""
    bounds: tuple[float, float, float, float]
    rect: tuple[float, float, float, float]

    def px(self, x: float) -> float:
        x0, x1, _, _ = self.bounds
        left, _, width, _ = self.rect
        return left + (x - x0) / (x1 - x0) * width

    def py(self, y: float) -> float:
        _, _, y0, y1 = self.bounds
        _, top, _, height = self.rect
        return top + height - (y - y0) / (y1 - y0) * height


def element(tag: str, text: str | None = None, **attributes) -> str:
    """An SVG element; attribute names use _ for - (stroke_width -> stroke-width)."""
    attrs = "".join(f" {k.rstrip('_').replace('_', '-')}={quoteattr(str(v))}"
                    for k, v in attributes.items())
    return f"<{tag}{attrs}/>" if text is None else f"<{tag}{attrs}>{escape(text)}</{tag}>"


def polyline(frame: Frame, xs: list[float], ys: list[float], colour: str, **style) -> str:
    stride = max(1, math.ceil(len(xs) / MAX_POLYLINE_POINTS))
    picked = list(range(0, len(xs), stride))
    if picked[-1] != len(xs) - 1:
        picked.append(len(xs) - 1)  # always end at the last state
    points = " ".join(f"{frame.px(xs[i]):.1f},{frame.py(ys[i]):.1f}" for i in picked)
    return element("polyline", fill="none", stroke=colour, stroke_width=1.3,
                   stroke_linejoin="round", points=points, **style)


def envelope(xs: list[float], ys: list[float]) -> tuple[list[float], list[float]]:
    """At most MAX_POLYLINE_POINTS points keeping each bucket's min and max, so that a fast
    oscillation keeps its extremes instead of aliasing into a slower one."""
    bucket = math.ceil(len(xs) / (MAX_POLYLINE_POINTS // 2))
    if bucket <= 1:
        return xs, ys
    out_x, out_y = [], []
    for start in range(0, len(xs), bucket):
        indices = range(start, min(start + bucket, len(xs)))
        for i in sorted((min(indices, key=ys.__getitem__), max(indices, key=ys.__getitem__))):
            out_x.append(xs[i])
            out_y.append(ys[i])
    return out_x, out_y


def axes(frame: Frame, x_ticks: list[float], y_ticks: list[float], x_label: str,
         y_label: str, x_scale: int = 0, y_scale: int = 0) -> list[str]:
    """A framed plot area with grid lines, ticks, tick labels and axis labels.

    Tick labels show value / 10^scale; each carries its exact value in data-value.
    """
    left, top, width, height = frame.rect
    bottom, right = top + height, left + width
    x_step = x_ticks[1] - x_ticks[0] if len(x_ticks) > 1 else 1.0
    y_step = y_ticks[1] - y_ticks[0] if len(y_ticks) > 1 else 1.0
    parts = ['<g class="x-axis">']
    for value in x_ticks:
        x = frame.px(value)
        parts += [element("line", x1=f"{x:.1f}", y1=top, x2=f"{x:.1f}", y2=bottom,
                          stroke="#e6e6e6"),
                  element("line", x1=f"{x:.1f}", y1=bottom, x2=f"{x:.1f}", y2=bottom + 5,
                          stroke="#444"),
                  element("text", format_tick(value / 10**x_scale, x_step / 10**x_scale),
                          class_="tick-label", data_value=repr(value), x=f"{x:.1f}",
                          y=bottom + 19, text_anchor="middle")]
    parts += [element("text", x_label, class_="axis-label", x=left + width / 2, y=bottom + 42,
                      text_anchor="middle"), "</g>", '<g class="y-axis">']
    for value in y_ticks:
        y = frame.py(value)
        parts += [element("line", x1=left, y1=f"{y:.1f}", x2=right, y2=f"{y:.1f}",
                          stroke="#e6e6e6"),
                  element("line", x1=left - 5, y1=f"{y:.1f}", x2=left, y2=f"{y:.1f}",
                          stroke="#444"),
                  element("text", format_tick(value / 10**y_scale, y_step / 10**y_scale),
                          class_="tick-label", data_value=repr(value), x=left - 8,
                          y=f"{y + 4:.1f}", text_anchor="end")]
    label_x = left - 58
    parts += [element("text", y_label, class_="axis-label", x=label_x, y=top + height / 2,
                      text_anchor="middle",
                      transform=f"rotate(-90 {label_x} {top + height / 2})"), "</g>",
              element("rect", x=left, y=top, width=width, height=height, fill="none",
                      stroke="#444")]
    return parts


def scaled_label(label: str, scale: int) -> str:
    """`label` with the power of ten the tick labels leave out, as in "... x 10^-8"."""
    if scale == 0:
        return label
    return f"{label}  \u00d7 10{str(scale).translate(SUPERSCRIPTS)}"


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


def legend_key(x: float, y: float, colour: str, label: str) -> list[str]:
    """A short thick line in `colour` followed by `label`, from x on the text baseline y."""
    return [element("line", x1=x, y1=y - 4, x2=x + 16, y2=y - 4, stroke=colour,
                    stroke_width=3),
            element("text", label, x=x + 20, y=y, fill=colour)]


def key_width(label: str) -> float:
    """How far the next legend entry starts after one labelled `label`."""
    return 20 + text_width(label) + 18


def text_width(text: str) -> float:
    """Roughly how wide `text` is at font size 13 (for spacing the legend)."""
    return 7.5 * len(text)


# --- the energy panel --------------------------------------------------------------------

@dataclass
class EnergyError:
    values: list[float]
    relative: bool                   # (E - E0) / |E0|; else E - E0 in J, because E0 = 0
    label: str

    @property
    def worst(self) -> float:
        return max(abs(v) for v in self.values)


def energy_error(energy: list[float]) -> EnergyError:
    """The error of each E(t) against E(0): relative when E(0) != 0, else absolute in J."""
    e0 = energy[0]
    if e0 != 0:
        return EnergyError([(e - e0) / abs(e0) for e in energy], True,
                           "relative energy error (E \u2212 E\u2080) / |E\u2080|")
    return EnergyError([e - e0 for e in energy], False,
                       "energy error E \u2212 E\u2080 (J), absolute: E\u2080 = 0")


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
    lo, hi, step = error_axis(error.values)
    frame = Frame((t0, t1, lo, hi), ENERGY_RECT)
    y_ticks = ticks_within(lo, hi, step)
    scale = decade_of(y_ticks)
    xs, ys = envelope(t, error.values)
    return ['<g id="energy-panel">',
            *axes(frame, t_ticks, y_ticks, "t (s)", scaled_label(error.label, scale),
                  y_scale=scale),
            element("line", x1=ENERGY_RECT[0], y1=f"{frame.py(0):.1f}",
                    x2=ENERGY_RECT[0] + ENERGY_RECT[2], y2=f"{frame.py(0):.1f}",
                    stroke="#999", stroke_dasharray="4 3"),
            polyline(frame, xs, ys, "#333", class_="energy-error"),
            "</g>"]


# --- the picture -------------------------------------------------------------------------

def render_svg(trajectory: Trajectory, name: str) -> str:
    """The whole picture as SVG text."""
    error = energy_error(trajectory.energy)
    ax, ay = plane_of_motion(trajectory)
    worst = (f"max |E \u2212 E\u2080| / |E\u2080| = {error.worst:.2e}" if error.relative
             else f"max |E \u2212 E\u2080| = {error.worst:.2e} J (E\u2080 = 0)")
    t = trajectory.t
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" '
             f'viewBox="0 0 {WIDTH} {HEIGHT}" font-family="sans-serif" font-size="13">',
             element("rect", width="100%", height="100%", fill="white"),
             element("text", f"{name}: particle paths in the {ax}{ay} plane", class_="title",
                     x=PATH_RECT[0] - 60, y=28, font_size=15, font_weight="bold"),
             element("text", f"{len(t)} states, t = {t[0]:g} \u2026 {t[-1]:g} s",
                     x=PATH_RECT[0] - 60, y=48, fill="#555"),
             element("text", f"{name}: energy error", class_="title", x=ENERGY_RECT[0] - 80,
                     y=28, font_size=15, font_weight="bold"),
             element("text", worst, class_="max-error", x=ENERGY_RECT[0] - 80, y=48,
                     fill="#555"),
             *path_panel(trajectory), *energy_panel(trajectory, error), "</svg>"]
    return "\n".join(parts) + "\n"


def write_svg(source: str, target: str, name: str | None = None) -> None:
    """Draws the trajectory CSV `source` into `target`; `name` defaults to the CSV's stem."""
    name = name or os.path.splitext(os.path.basename(source))[0]
    svg = render_svg(read_trajectory(source), name)
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
