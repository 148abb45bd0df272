# SPDX-License-Identifier: BSD-3-Clause
"""gencoord/tool/timeseries_svg.py: stacked panels of time series, read back with xml.etree: one
polyline per series at the right pixels, one time range for all panels, bounded point counts,
and one-line errors for CSVs that cannot be drawn."""

from __future__ import annotations

import contextlib
import io
import math
import os
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET
from pathlib import Path

from gencoord.tool import timeseries_svg as ts
from gencoord.tool.errors import ToolError
from gencoord.tool.svg_plot import MAX_POLYLINE_POINTS

SVG = "{http://www.w3.org/2000/svg}"
REPO = Path(__file__).resolve().parents[2]


def cart_pole(steps: int = 201, duration: float = 10.0):
    """A damped cart-pole's states: t, and the panels Cart / Angles / Force."""
    t = [duration * k / (steps - 1) for k in range(steps)]
    x = [0.5 * math.exp(-s / 3) * math.cos(2 * s) for s in t]
    theta1 = [0.2 * math.exp(-s / 2) * math.sin(3 * s) for s in t]
    theta2 = [-0.1 * math.exp(-s / 2) * math.sin(5 * s + 1) for s in t]
    u = [30 * math.exp(-s) * math.cos(4 * s) for s in t]
    panels = [("Cart (m)", {"x": x}), ("Angles (rad)", {"theta1": theta1, "theta2": theta2}),
              ("Force (N)", {"u": u})]
    return t, panels


def csv_text(t, columns: dict[str, list[float]]) -> str:
    lines = [",".join(["t", *columns])]
    lines += [",".join(repr(v) for v in [s, *(values[k] for values in columns.values())])
              for k, s in enumerate(t)]
    return "\n".join(lines) + "\n"


def points(polyline: ET.Element) -> list[tuple[float, float]]:
    return [tuple(map(float, pair.split(","))) for pair in polyline.get("points").split()]


class Panel:
    """One panel of the picture with its plot rectangle and axes read back."""

    def __init__(self, element: ET.Element):
        self.element = element
        rect = element.find(f"{SVG}rect")
        self.rect = tuple(float(rect.get(key)) for key in ("x", "y", "width", "height"))

    def lines(self) -> list[ET.Element]:
        return self.element.findall(f"{SVG}polyline")

    def line(self, name: str) -> ET.Element:
        return self.element.find(f"{SVG}polyline[@data-name='{name}']")

    def tick_labels(self, which: str) -> list[ET.Element]:
        return self.element.findall(f"{SVG}g[@class='{which}-axis']/{SVG}text[@class='tick-label']")

    def tick_values(self, which: str) -> list[float]:
        return [float(label.get("data-value")) for label in self.tick_labels(which)]

    def pixel_of(self, which: str, value: float) -> float:
        """Where `value` lands on axis `which`, interpolated between its first and last tick."""
        labels = self.tick_labels(which)
        coordinate = "x" if which == "x" else "y"
        v0, p0 = float(labels[0].get("data-value")), float(labels[0].get(coordinate))
        v1, p1 = float(labels[-1].get("data-value")), float(labels[-1].get(coordinate))
        pixel = p0 + (value - v0) * (p1 - p0) / (v1 - v0)
        return pixel if which == "x" else pixel - 4  # y labels sit 4 px below their tick


def render(t, panels, title="cart-pole") -> tuple[ET.Element, list[Panel]]:
    root = ET.fromstring(ts.render_timeseries_svg(t, panels, title))
    return root, [Panel(g) for g in root.findall(f"{SVG}g[@class='panel']")]


class RenderTest(unittest.TestCase):

    def setUp(self):
        self.t, self.panels = cart_pole()
        self.root, self.drawn = render(self.t, self.panels)

    def test_parses_as_svg_with_the_title_and_one_panel_per_entry(self):
        self.assertEqual(self.root.tag, f"{SVG}svg")
        self.assertEqual(self.root.find(f"{SVG}text[@class='title']").text, "cart-pole")
        self.assertEqual([p.element.get("data-label") for p in self.drawn],
                         ["Cart (m)", "Angles (rad)", "Force (N)"])
        labels = [p.element.find(f"{SVG}g[@class='y-axis']/{SVG}text[@class='axis-label']").text
                  for p in self.drawn]
        self.assertEqual(labels, ["Cart (m)", "Angles (rad)", "Force (N)"])

    def test_one_polyline_per_series_each_in_its_own_colour_with_a_legend(self):
        for (label, series), panel in zip(self.panels, self.drawn):
            with self.subTest(panel=label):
                lines = panel.lines()
                self.assertEqual([line.get("data-name") for line in lines], list(series))
                colours = [line.get("stroke") for line in lines]
                self.assertEqual(len(set(colours)), len(colours))
                legend = panel.element.find(f"{SVG}g[@class='legend']")
                keys = legend.findall(f"{SVG}text")
                self.assertEqual([key.text for key in keys], list(series))
                self.assertEqual([key.get("fill") for key in keys], colours)

    def test_panels_are_stacked_without_overlap(self):
        rects = [panel.rect for panel in self.drawn]
        for upper, lower in zip(rects, rects[1:]):
            self.assertGreater(lower[1], upper[1] + upper[3] + 30)
        self.assertLessEqual(rects[-1][1] + rects[-1][3] + 42, float(self.root.get("height")))

    def test_points_land_on_the_data(self):
        angles = self.drawn[1]
        theta2 = self.panels[1][1]["theta2"]
        drawn = points(angles.line("theta2"))
        self.assertEqual(len(drawn), len(self.t))  # short enough to keep every sample
        left, _, width, _ = angles.rect
        self.assertAlmostEqual(drawn[0][0], left, delta=0.06)       # t = 0 at the left edge
        self.assertAlmostEqual(drawn[-1][0], left + width, delta=0.06)  # t = 10 at the right
        for k in (0, 37, 100, 200):
            with self.subTest(sample=k):
                self.assertAlmostEqual(drawn[k][0], angles.pixel_of("x", self.t[k]), delta=0.1)
                self.assertAlmostEqual(drawn[k][1], angles.pixel_of("y", theta2[k]), delta=0.1)

    def test_points_agree_with_the_panel_frames(self):
        frames = ts.panel_frames(self.t, self.panels)
        for (label, series), panel, frame in zip(self.panels, self.drawn, frames):
            self.assertEqual(tuple(frame.rect), panel.rect)
            for name, values in series.items():
                with self.subTest(panel=label, series=name):
                    drawn = points(panel.line(name))
                    self.assertAlmostEqual(drawn[50][0], frame.px(self.t[50]), delta=0.06)
                    self.assertAlmostEqual(drawn[50][1], frame.py(values[50]), delta=0.06)
                    _, _, y0, y1 = frame.bounds
                    self.assertLess(y0, min(values))
                    self.assertGreater(y1, max(values))

    def test_panels_share_the_time_range(self):
        frames = ts.panel_frames(self.t, self.panels)
        self.assertEqual({frame.bounds[:2] for frame in frames}, {(0.0, 10.0)})
        self.assertEqual({(p.rect[0], p.rect[2]) for p in self.drawn}, {self.drawn[0].rect[::2]})
        ticks = [panel.tick_values("x") for panel in self.drawn]
        self.assertEqual(ticks, [ticks[0]] * len(ticks))
        self.assertEqual((ticks[0][0], ticks[0][-1]), (0.0, 10.0))
        ends = {(points(line)[0][0], points(line)[-1][0])
                for panel in self.drawn for line in panel.lines()}
        self.assertEqual(len(ends), 1, ends)

    def test_only_the_bottom_panel_names_the_time_axis(self):
        labels = [p.element.find(f"{SVG}g[@class='x-axis']/{SVG}text[@class='axis-label']").text
                  for p in self.drawn]
        self.assertEqual(labels, [None, None, "t (s)"])


class DecimationTest(unittest.TestCase):

    def test_long_series_are_bounded_and_keep_their_extremes(self):
        steps = 50001
        t = [20.0 * k / (steps - 1) for k in range(steps)]
        # one period every 26 samples, the stride that plain thinning to the limit would take:
        # it would see a constant, the envelope keeps the swing
        fast = [math.sin(2 * math.pi * k / 26 + 0.3) for k in range(steps)]
        slow = [s / 20.0 for s in t]
        _, drawn = render(t, [("Signals", {"fast": fast, "slow": slow})])
        panel = drawn[0]
        for name in ("fast", "slow"):
            with self.subTest(series=name):
                self.assertLessEqual(len(points(panel.line(name))), MAX_POLYLINE_POINTS)
        ys = [y for _, y in points(panel.line("fast"))]
        self.assertAlmostEqual(min(ys), panel.pixel_of("y", 1.0), delta=0.5)
        self.assertAlmostEqual(max(ys), panel.pixel_of("y", -1.0), delta=0.5)
        xs = [x for x, _ in points(panel.line("slow"))]
        self.assertEqual(xs, sorted(xs))
        self.assertAlmostEqual(xs[-1], panel.rect[0] + panel.rect[2], delta=0.06)


class EdgeCaseTest(unittest.TestCase):

    def test_non_finite_values_are_left_out(self):
        t = [0.0, 1.0, 2.0, 3.0]
        _, drawn = render(t, [("a", {"a": [0.0, math.nan, 2.0, math.inf]}),
                              ("b", {"b": [math.nan] * 4})])
        self.assertEqual(len(points(drawn[0].line("a"))), 2)
        self.assertLess(max(drawn[0].tick_values("y")), 10)
        self.assertEqual(drawn[1].line("b").get("points"), "")

    def test_constant_series_and_a_single_sample_still_get_axes(self):
        for t, values in (([0.0, 1.0, 2.0], [0.0, 0.0, 0.0]), ([3.0], [5.0])):
            with self.subTest(samples=len(t)):
                _, drawn = render(t, [("c", {"c": values})])
                self.assertGreaterEqual(len(drawn[0].tick_values("y")), 2)
                self.assertGreaterEqual(len(drawn[0].tick_values("x")), 2)
                self.assertEqual(len(points(drawn[0].line("c"))), len(t))

    def test_inconsistent_input_is_refused(self):
        with self.assertRaisesRegex(ValueError, "'a' has 2 values for 3"):
            ts.render_timeseries_svg([0.0, 1.0, 2.0], [("a", {"a": [1.0, 2.0]})], "x")
        with self.assertRaisesRegex(ValueError, "t decreases at sample 2"):
            ts.render_timeseries_svg([0.0, 1.0, 0.5], [("a", {"a": [1.0, 2.0, 3.0]})], "x")
        with self.assertRaisesRegex(ValueError, "no panels"):
            ts.render_timeseries_svg([0.0], [], "x")

    def test_many_series_wrap_their_legend_into_rows_above_the_panel(self):
        t = [0.0, 1.0]
        series = {f"a_rather_long_state_name_{k}": [0.0, float(k)] for k in range(12)}
        _, drawn = render(t, [("first", {"a": [0.0, 1.0]}), ("many", series)])
        keys = drawn[1].element.findall(f"{SVG}g[@class='legend']/{SVG}text")
        rows = sorted({float(key.get("y")) for key in keys})
        self.assertGreater(len(rows), 1)
        self.assertLess(rows[-1], drawn[1].rect[1])
        self.assertGreater(rows[0], drawn[0].rect[1] + drawn[0].rect[3] + 19)
        left, _, width, _ = drawn[1].rect
        self.assertTrue(all(float(key.get("x")) < left + width for key in keys))


class WriteTest(unittest.TestCase):

    def setUp(self):
        directory = tempfile.TemporaryDirectory(prefix="gencoord-timeseries-")
        self.addCleanup(directory.cleanup)
        self.folder = Path(directory.name)
        t, panels = cart_pole(steps=51)
        columns = {name: values for _, series in panels for name, values in series.items()}
        self.source = self.folder / "run.csv"
        self.source.write_text(csv_text(t, columns))
        self.target = self.folder / "run.svg"

    def run_main(self, *arguments: str) -> tuple[int, str]:
        stderr = io.StringIO()
        with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
            status = ts.main([*map(str, arguments)])
        return status, stderr.getvalue()

    def test_default_is_one_panel_per_column_titled_with_the_stem(self):
        ts.write_timeseries_svg(str(self.source), str(self.target))
        root = ET.parse(self.target).getroot()
        panels = root.findall(f"{SVG}g[@class='panel']")
        self.assertEqual([p.get("data-label") for p in panels], ["x", "theta1", "theta2", "u"])
        self.assertEqual(root.find(f"{SVG}text[@class='title']").text, "run")

    def test_command_line_panels_and_title(self):
        status, _ = self.run_main(self.source, self.target, "--panel",
                                  "Angles (rad)=theta1,theta2", "--panel", "u", "--title",
                                  "LQR")
        self.assertEqual(status, 0)
        root = ET.parse(self.target).getroot()
        panels = [Panel(g) for g in root.findall(f"{SVG}g[@class='panel']")]
        self.assertEqual([p.element.get("data-label") for p in panels], ["Angles (rad)", "u"])
        self.assertEqual([line.get("data-name") for line in panels[0].lines()],
                         ["theta1", "theta2"])
        self.assertEqual(root.find(f"{SVG}text[@class='title']").text, "LQR")

    def test_panel_specification(self):
        self.assertEqual(ts.parse_panel("Angles (rad)=theta1, theta2"),
                         ("Angles (rad)", ["theta1", "theta2"]))
        self.assertEqual(ts.parse_panel("theta1,theta2"), ("theta1, theta2", ["theta1", "theta2"]))
        self.assertEqual(ts.parse_panel("x = 1=q"), ("x = 1", ["q"]))

    def test_a_missing_column_names_the_file_and_the_column(self):
        with self.assertRaises(ToolError) as caught:
            ts.write_timeseries_svg(str(self.source), str(self.target),
                                    [("Angles", ["theta1", "theta3"])])
        self.assertIn(str(self.source), str(caught.exception))
        self.assertIn("'theta3'", str(caught.exception))
        self.assertFalse(self.target.exists())
        status, message = self.run_main(self.source, self.target, "--panel", "A=theta3")
        self.assertEqual(status, 2)
        self.assertEqual(len(message.strip().splitlines()), 1, message)
        self.assertIn(str(self.source), message)
        self.assertIn("no column 'theta3'", message)

    def test_unreadable_inputs_give_one_line(self):
        cases = {"missing.csv": None, "empty.csv": "", "header.csv": "t,x\n",
                 "no_t.csv": "time,x\n0,1\n", "text.csv": "t,x\n0,1\n1,fast\n"}
        expected = {"missing.csv": "No such file", "empty.csv": "empty",
                    "header.csv": "no rows of data", "no_t.csv": "no column 't'",
                    "text.csv": "run.csv:3: column 'x': 'fast'"}
        for name, text in cases.items():
            with self.subTest(file=name):
                source = self.folder / name
                if text is not None:
                    source.write_text(text)
                status, message = self.run_main(source, self.target)
                self.assertEqual(status, 2)
                self.assertEqual(len(message.strip().splitlines()), 1, message)
                self.assertIn(str(source), message)
                self.assertIn(expected[name].replace("run.csv", name), message)

    def test_module_command_exits_2_without_a_traceback(self):
        result = subprocess.run(
            [sys.executable, "-m", "gencoord.tool.timeseries_svg", str(self.source),
             str(self.target), "--panel", "Angles=theta1,nope"], cwd=REPO, capture_output=True,
            text=True, timeout=60, env=dict(os.environ, PYTHONPATH=str(REPO / "python")))
        self.assertEqual(result.returncode, 2)
        self.assertNotIn("Traceback", result.stderr)
        self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)
        self.assertIn("no column 'nope'", result.stderr)
        self.assertIn(str(self.source), result.stderr)


if __name__ == "__main__":
    unittest.main()
