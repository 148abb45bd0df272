# SPDX-License-Identifier: BSD-3-Clause
"""Draws time series from a CSV as an SVG: stacked panels that share one time axis. By hand:

    python3 -m gencoord.tool.timeseries_svg run.csv run.svg \\
        --panel 'Angles (rad)=theta1,theta2' --panel 'Cart (m)=x' [--title TITLE]

Standard library only; the drawing helpers are trajectory_svg's. The CSV has a header row
naming its columns, one of them `t` (in seconds), then rows of numbers. Each --panel
'Label=col1,col2' draws those columns in one panel labelled Label (without "Label=" the
label is the column names); without --panel every column but t gets a panel of its own.
Each series is a coloured line, named in a legend above its panel. Values that are not
finite (a run that diverged) are left out of the lines and of the axis ranges. The title
defaults to the CSV file's stem.
"""
from __future__ import annotations

import argparse
import math
import os
import sys
from xml.sax.saxutils import quoteattr

from gencoord.tool.csv_columns import read_columns
from gencoord.tool.errors import ToolError
from gencoord.tool.svg_plot import (COLOURS, Frame, axes, decade_of, element, envelope, key_width,
                                    legend_key, nice_step, padded_range, polyline, scaled_label,
                                    ticks_within, time_axis)
from gencoord.tool.trajectory_svg import WIDTH

PLOT_LEFT, PLOT_WIDTH = 90, 880      # the y tick labels and the rotated label fit left of it
PANEL_HEIGHT = 170
FIRST_TOP = 62                       # below the title lines
LEGEND_ROW = 20                      # a row of legend keys above each panel
PANEL_GAP = 36                       # below a panel: its time tick labels, then a margin
BOTTOM_MARGIN = 58                   # below the last panel: tick labels and "t (s)"


# --- the picture -------------------------------------------------------------------------

def check_series(t: list[float], panels: list[tuple[str, dict[str, list[float]]]]) -> None:
    """ValueError unless there is data, every series is as long as t, and t is finite and
    does not decrease (a line drawn over a t that jumps back would cross itself)."""
    if not t:
        raise ValueError("no samples: t is empty")
    if not panels:
        raise ValueError("nothing to draw: no panels")
    for k, value in enumerate(t):
        if not math.isfinite(value):
            raise ValueError(f"t is not finite at sample {k}: {value}")
        if k and value < t[k - 1]:
            raise ValueError(f"t decreases at sample {k}: {t[k - 1]:g} then {value:g}")
    for label, series in panels:
        if not series:
            raise ValueError(f"panel {label!r} has no series")
        for name, values in series.items():
            if len(values) != len(t):
                raise ValueError(f"series {name!r} has {len(values)} values for {len(t)} "
                                 "samples of t")


def finite_points(t: list[float], values: list[float]) -> tuple[list[float], list[float]]:
    kept = [(x, y) for x, y in zip(t, values) if math.isfinite(y)]
    return [x for x, _ in kept], [y for _, y in kept]


def legend_rows(names: list[str]) -> list[list[str]]:
    """The series names split into rows of legend keys no wider than the panel."""
    rows: list[list[str]] = [[]]
    width = 0.0
    for name in names:
        if rows[-1] and width + key_width(name) > PLOT_WIDTH:
            rows.append([])
            width = 0.0
        rows[-1].append(name)
        width += key_width(name)
    return rows


def panel_layout(panels: list[tuple[str, dict[str, list[float]]]]
                 ) -> tuple[list[tuple[float, float, float, float]], int]:
    """Each panel's plot rectangle (left, top, width, height), top to bottom, and the
    picture's height; room is left above each panel for its legend rows."""
    rects: list[tuple[float, float, float, float]] = []
    top = FIRST_TOP
    for _, series in panels:
        top += LEGEND_ROW * len(legend_rows(list(series))) + 6
        rects.append((PLOT_LEFT, top, PLOT_WIDTH, PANEL_HEIGHT))
        top += PANEL_HEIGHT + PANEL_GAP
    return rects, round(top - PANEL_GAP + BOTTOM_MARGIN)


def value_axis(series: dict[str, list[float]]) -> tuple[float, float, list[float]]:
    """Padded bounds around the finite values of a panel's series, and ticks inside them."""
    values = [v for vs in series.values() for v in vs if math.isfinite(v)]
    lo, hi = padded_range(values) if values else (-1.0, 1.0)
    return lo, hi, ticks_within(lo, hi, nice_step(hi - lo))


def panel_frames(t: list[float], panels: list[tuple[str, dict[str, list[float]]]]
                 ) -> list[Frame]:
    """The frame of each panel: one time range for all, each its own value range."""
    t0, t1, _ = time_axis(t)
    rects, _ = panel_layout(panels)
    return [Frame((t0, t1, *value_axis(series)[:2]), rect)
            for (_, series), rect in zip(panels, rects)]


def series_line(frame: Frame, t: list[float], name: str, values: list[float],
                colour: str) -> str:
    """The series as one polyline, thinned to its envelope so long runs stay small."""
    xs, ys = finite_points(t, values)
    if not xs:
        return element("polyline", class_="series", data_name=name, fill="none",
                       stroke=colour, points="")
    xs, ys = envelope(xs, ys)
    return polyline(frame, xs, ys, colour, class_="series", data_name=name)


def panel(k: int, label: str, series: dict[str, list[float]], t: list[float], frame: Frame,
          t_ticks: list[float], last: bool) -> list[str]:
    left, top, _, _ = frame.rect
    _, _, y_ticks = value_axis(series)
    scale = decade_of(y_ticks)
    parts = [f'<g class="panel" id="panel-{k}" data-label={quoteattr(label)}>',
             *axes(frame, t_ticks, y_ticks, "t (s)" if last else "", scaled_label(label, scale),
                   y_scale=scale),
             '<g class="legend">']
    rows = legend_rows(list(series))
    colours = {name: COLOURS[n % len(COLOURS)] for n, name in enumerate(series)}
    for r, row in enumerate(rows):
        x, y = left, top - 10 - LEGEND_ROW * (len(rows) - 1 - r)
        for name in row:
            parts += legend_key(x, y, colours[name], name)
            x += key_width(name)
    parts.append("</g>")
    parts += [series_line(frame, t, name, values, colours[name])
              for name, values in series.items()]
    return parts + ["</g>"]


def render_timeseries_svg(t: list[float], panels: list[tuple[str, dict[str, list[float]]]],
                          title: str) -> str:
    """One panel per entry (panel title/y label, {series name: values}), stacked vertically,
    sharing the time axis; each series a coloured polyline with a legend."""
    check_series(t, panels)
    frames = panel_frames(t, panels)
    _, height = panel_layout(panels)
    _, _, t_ticks = time_axis(t)
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{height}" '
             f'viewBox="0 0 {WIDTH} {height}" font-family="sans-serif" font-size="13">',
             element("rect", width="100%", height="100%", fill="white"),
             element("text", title, class_="title", x=20, y=28, font_size=15,
                     font_weight="bold"),
             element("text", f"{len(t)} samples, t = {t[0]:g} \u2026 {t[-1]:g} s",
                     class_="subtitle", x=20, y=48, fill="#555")]
    for k, ((label, series), frame) in enumerate(zip(panels, frames)):
        parts += panel(k, label, series, t, frame, t_ticks, k == len(panels) - 1)
    return "\n".join(parts + ["</svg>"]) + "\n"


def write_timeseries_svg(source_csv: str, target_svg: str,
                         panels: list[tuple[str, list[str]]] | None = None,
                         title: str | None = None) -> None:
    """Reads a CSV with a 't' column (header row, then numbers) and draws the named columns,
    grouped into panels; by default one panel per column."""
    columns = read_columns(source_csv)
    if panels is None:
        panels = [(name, [name]) for name in columns if name != "t"]
        if not panels:
            raise ToolError(f"{source_csv}: no columns to draw besides 't'")
    for _, names in panels:
        for name in names:
            if name not in columns:
                raise ToolError(f"{source_csv}: no column {name!r} "
                                f"(columns: {', '.join(columns)})")
    title = title if title is not None else os.path.splitext(os.path.basename(source_csv))[0]
    try:
        svg = render_timeseries_svg(
            columns["t"], [(label, {name: columns[name] for name in names})
                           for label, names in panels], title)
    except ValueError as error:
        raise ToolError(f"{source_csv}: {error}") from None
    try:
        with open(target_svg, "w", encoding="utf-8") as handle:
            handle.write(svg)
    except OSError as error:
        raise ToolError(f"{target_svg}: {error.strerror or error}") from None


# --- the command line --------------------------------------------------------------------

def parse_panel(spec: str) -> tuple[str, list[str]]:
    """'Label=col1,col2' as (label, columns); the label defaults to the column names."""
    label, _, names = spec.rpartition("=")
    columns = [name.strip() for name in names.split(",") if name.strip()]
    if not columns:
        raise argparse.ArgumentTypeError(f"no columns in {spec!r}; expected 'Label=col1,col2'")
    return label.strip() or ", ".join(columns), columns


def main(argv: list[str] | None = None) -> int:
    """Exit status 2, with one line on stderr, for a CSV that cannot be drawn."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("source", help="CSV with a header row and a 't' column")
    parser.add_argument("target", help="SVG file to write")
    parser.add_argument("--panel", action="append", type=parse_panel, metavar="'LABEL=A,B'",
                        help="a panel drawing columns A and B, labelled LABEL (repeatable; "
                             "default: one panel per column)")
    parser.add_argument("--title", help="the picture's title (default: the CSV's stem)")
    args = parser.parse_args(argv)
    try:
        write_timeseries_svg(args.source, args.target, args.panel, args.title)
    except ToolError as error:
        print(f"{parser.prog}: error: {error}", file=sys.stderr)
        return 2
    print(f"picture     {args.target}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
