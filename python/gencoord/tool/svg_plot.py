# SPDX-License-Identifier: BSD-3-Clause
"""SVG charts from the standard library: 1-2-5 ticks, frames that map data onto pixels, axes
with grid and labels, polylines thinned to a few thousand points, legend keys. The trajectory
and time-series plots (trajectory_svg.py, timeseries_svg.py) draw with them."""

from __future__ import annotations

import math
from dataclasses import dataclass
from xml.sax.saxutils import escape, quoteattr

COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2"]
MAX_POLYLINE_POINTS = 2000           # keeps the file small; more is invisible at this size
TICK_TARGET = 6                      # about this many ticks per axis
SUPERSCRIPTS = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


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
