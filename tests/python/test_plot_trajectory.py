# SPDX-License-Identifier: BSD-3-Clause
"""gencoord/tool/trajectory_svg.py: axes, ticks, units, fixed points and the energy error axis of
the SVG it draws, read back with xml.etree from small synthetic trajectories."""

from __future__ import annotations

import io
import math
import tempfile
import unittest
import xml.etree.ElementTree as ET
from pathlib import Path

from gencoord.tool import svg_plot
from gencoord.tool import trajectory_svg as plot

SVG = "{http://www.w3.org/2000/svg}"
SUPERSCRIPT_DIGITS = str.maketrans(
    "\u207b\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079", "-0123456789")


def pendulum_csv(energy, pivot_y=lambda t: 0.0, length=1.5, steps=501, duration=5.0,
                 plane="xy") -> str:
    """A pendulum swinging about a pivot at (0, pivot_y(t)), in csv_writer.hpp's layout;
    `plane` "xz" makes it a 3D model swinging in the xz plane."""
    axes = "xyz" if plane == "xz" else "xy"
    header = ["t", "q_theta", "v_theta", "energy",
              *(f"bob_{a}" for a in axes), *(f"fixed:pivot_{a}" for a in axes)]
    lines = [",".join(header)]
    for k in range(steps):
        t = duration * k / (steps - 1)
        theta = 0.8 * math.cos(2 * t)
        pivot = pivot_y(t)
        horizontal, vertical = length * math.sin(theta), pivot - length * math.cos(theta)
        if plane == "xz":
            bob, anchor = [horizontal, 0.0, vertical], [0.0, 0.0, pivot]
        else:
            bob, anchor = [horizontal, vertical], [0.0, pivot]
        lines.append(",".join(repr(v) for v in [t, theta, -1.6 * math.sin(2 * t), energy(t),
                                                *bob, *anchor]))
    return "\n".join(lines) + "\n"


def render(csv_text: str, name: str = "test_model") -> ET.Element:
    trajectory = plot.parse_trajectory(io.StringIO(csv_text))
    return ET.fromstring(plot.render_svg(trajectory, name))


def number(label: str) -> float:
    return float(label.replace("\u2212", "-"))


class Panel:
    """One panel of the picture, found by id, with its axes read back."""

    def __init__(self, root: ET.Element, panel_id: str):
        self.element = root.find(f".//{SVG}g[@id='{panel_id}']")
        assert self.element is not None, panel_id

    def axis(self, which: str) -> ET.Element:
        return self.element.find(f"{SVG}g[@class='{which}-axis']")

    def tick_labels(self, which: str) -> list[ET.Element]:
        return self.axis(which).findall(f"{SVG}text[@class='tick-label']")

    def tick_values(self, which: str) -> list[float]:
        return [float(label.get("data-value")) for label in self.tick_labels(which)]

    def axis_label(self, which: str) -> str:
        return self.axis(which).find(f"{SVG}text[@class='axis-label']").text

    def pixels_per_unit(self, which: str) -> float:
        labels = self.tick_labels(which)
        coordinate = "x" if which == "x" else "y"
        first, second = labels[0], labels[1]
        return abs((float(second.get(coordinate)) - float(first.get(coordinate)))
                   / (float(second.get("data-value")) - float(first.get("data-value"))))

    def pixel_of(self, which: str, value: float) -> float:
        """Where `value` lands on axis `which`, interpolated between its first two ticks."""
        labels = self.tick_labels(which)
        coordinate = "x" if which == "x" else "y"
        v0, p0 = float(labels[0].get("data-value")), float(labels[0].get(coordinate))
        v1, p1 = float(labels[1].get("data-value")), float(labels[1].get(coordinate))
        pixel = p0 + (value - v0) * (p1 - p0) / (v1 - v0)
        return pixel if which == "x" else pixel - 4  # y labels sit 4 px below their tick


def is_one_two_five(step: float) -> bool:
    mantissa = step / 10 ** math.floor(math.log10(step) + 1e-12)
    return any(math.isclose(mantissa, m) for m in (1, 2, 5))


class NiceTicksTest(unittest.TestCase):

    def test_steps_are_one_two_or_five_times_a_power_of_ten(self):
        for span in (7.0, 10.0, 0.37, 3.3e-7, 12345.0, 1.0):
            with self.subTest(span=span):
                step = svg_plot.nice_step(span)
                self.assertTrue(is_one_two_five(step), step)
                self.assertTrue(3 <= span / step <= 15, (span, step))
        self.assertEqual(svg_plot.nice_step(10.0, 5), 2.0)
        self.assertAlmostEqual(svg_plot.nice_step(0.37, 6), 0.05)

    def test_ticks_are_the_steps_multiples_inside_the_range(self):
        self.assertEqual(svg_plot.ticks_within(-0.23, 1.07, 0.5), [0.0, 0.5, 1.0])
        self.assertEqual(svg_plot.ticks_within(0.1, 0.35, 0.1), [0.1, 0.2, 0.3])
        self.assertEqual([svg_plot.format_tick(v, 0.5) for v in (-1.0, 0.0, 1.5)],
                         ["\u22121.0", "0", "1.5"])


class PathPanelTest(unittest.TestCase):

    def setUp(self):
        self.root = render(pendulum_csv(lambda t: 10.0))
        self.panel = Panel(self.root, "path-panel")

    def test_axes_are_labelled_in_metres(self):
        self.assertEqual(self.panel.axis_label("x"), "x (m)")
        self.assertEqual(self.panel.axis_label("y"), "y (m)")

    def test_tick_labels_are_evenly_stepped_nice_values_covering_the_motion(self):
        # the bob swings over x in [-1.076, 1.076], y in [-1.5, -1.04]; the pivot is at 0
        for which, low, high in (("x", -1.076, 1.076), ("y", -1.5, 0.0)):
            with self.subTest(axis=which):
                labels = self.panel.tick_labels(which)
                values = [number(label.text) for label in labels]
                self.assertEqual(values, self.panel.tick_values(which))
                steps = {round(b - a, 12) for a, b in zip(values, values[1:])}
                self.assertEqual(len(steps), 1, values)
                step = steps.pop()
                self.assertTrue(is_one_two_five(step), step)
                self.assertGreaterEqual(len(values), 4)
                self.assertLessEqual(values[0], low + step)
                self.assertGreaterEqual(values[-1], high - step)

    def test_equal_aspect(self):
        self.assertAlmostEqual(self.panel.pixels_per_unit("x"), self.panel.pixels_per_unit("y"),
                               delta=0.5)

    def test_the_fixed_pivot_is_marked_at_its_position_without_a_path(self):
        points = self.panel.element.findall(f"{SVG}g[@class='fixed-point']")
        self.assertEqual([p.get("data-name") for p in points], ["pivot"])
        marker = points[0].find(f"{SVG}circle[@class='fixed-point-marker']")
        self.assertIsNotNone(marker)
        self.assertAlmostEqual(float(marker.get("cx")), self.panel.pixel_of("x", 0.0), delta=0.6)
        self.assertAlmostEqual(float(marker.get("cy")), self.panel.pixel_of("y", 0.0), delta=0.6)
        self.assertIsNone(points[0].find(f"{SVG}polyline"))
        self.assertEqual([p.get("data-name") for p in
                          self.panel.element.findall(f"{SVG}g[@class='particle']")], ["bob"])

    def test_a_moving_fixed_point_gets_a_light_path_and_a_marker_at_its_last_position(self):
        duration = 5.0
        root = render(pendulum_csv(lambda t: 10.0, pivot_y=lambda t: 0.3 * math.cos(3 * t),
                                   duration=duration))
        panel = Panel(root, "path-panel")
        point = panel.element.find(f"{SVG}g[@class='fixed-point']")
        path = point.find(f"{SVG}polyline[@class='fixed-point-path']")
        self.assertIsNotNone(path)
        self.assertLess(float(path.get("stroke-opacity")), 1.0)
        marker = point.find(f"{SVG}circle[@class='fixed-point-marker']")
        self.assertAlmostEqual(float(marker.get("cy")),
                               panel.pixel_of("y", 0.3 * math.cos(3 * duration)), delta=0.6)

    def test_a_three_dimensional_swing_is_drawn_in_its_plane(self):
        panel = Panel(render(pendulum_csv(lambda t: 1.0, plane="xz")), "path-panel")
        self.assertEqual(panel.axis_label("x"), "x (m)")
        self.assertEqual(panel.axis_label("y"), "z (m)")


class EnergyPanelTest(unittest.TestCase):

    def test_relative_error_axis_spans_the_data_with_its_power_of_ten(self):
        # E(t) = 10 (1 + 3e-7 t): the relative error grows linearly to 1.5e-6 at t = 5
        root = render(pendulum_csv(lambda t: 10.0 * (1 + 3e-7 * t)))
        panel = Panel(root, "energy-panel")
        label = panel.axis_label("y")
        self.assertIn("relative", label)
        self.assertIn("(E \u2212 E\u2080) / |E\u2080|", label)
        self.assertIn("\u00d7 10", label)
        exponent = int(label.rsplit("10", 1)[1].translate(SUPERSCRIPT_DIGITS))
        shown = [number(t.text) * 10.0 ** exponent for t in panel.tick_labels("y")]
        for value, exact in zip(shown, panel.tick_values("y")):
            self.assertAlmostEqual(value, exact, delta=1e-12)
        self.assertLessEqual(min(shown), 0.0)
        self.assertGreaterEqual(max(shown), 1.5e-6 * (1 - 1e-9))
        self.assertLess(max(shown) - min(shown), 3 * 1.5e-6)  # no wasted decades
        title = root.find(f".//{SVG}text[@class='max-error']").text
        self.assertIn("1.50e-06", title)

    def test_a_model_that_does_not_conserve_energy_plots_its_change(self):
        trajectory = plot.parse_trajectory(io.StringIO(pendulum_csv(lambda t: 10.0 - t)))
        root = ET.fromstring(plot.render_svg(trajectory, "damped", conserved=False))
        label = Panel(root, "energy-panel").axis_label("y")
        self.assertIn("relative energy change", label)
        titles = [t.text for t in root.iter(f"{SVG}text") if t.get("class") == "title"]
        self.assertIn("damped: energy change", titles)
        self.assertNotIn("error", " ".join([label, *titles]))

    def test_a_dissipative_model_plots_its_energy_change_with_the_dampers_work(self):
        """With a work column, E - E0 and W share the panel, and the balance is the figure."""
        text = pendulum_csv(lambda t: 10.0 - t)
        header, *rows = text.splitlines()
        columns = header.split(",")
        at = columns.index("energy") + 1
        lines = [",".join([*columns[:at], "work", *columns[at:]])]
        for row in rows:  # W = -t + 1e-4 t^2: the balance E - E0 - W = -1e-4 t^2
            values = row.split(",")
            t = float(values[0])
            lines.append(",".join([*values[:at], repr(-t + 1e-4 * t * t), *values[at:]]))
        trajectory = plot.parse_trajectory(io.StringIO("\n".join(lines) + "\n"))
        root = ET.fromstring(plot.render_svg(trajectory, "damped", conserved=False))
        panel = Panel(root, "energy-panel")
        self.assertIsNotNone(panel.element.find(f"{SVG}polyline[@class='work']"))
        self.assertIn("and W", panel.axis_label("y"))
        summary = root.find(f".//{SVG}text[@class='max-error']").text
        self.assertIn("E \u2212 E\u2080 \u2212 W", summary)
        self.assertIn(f"{1e-4 * 25 / 10:.2e}", summary)  # at t = 5 s, relative to E0 = 10 J
        values = panel.tick_values("y")
        self.assertLessEqual(values[0], -0.5)  # the axis holds both curves

    def test_time_axis_in_seconds_from_start_to_end(self):
        panel = Panel(render(pendulum_csv(lambda t: 10.0)), "energy-panel")
        self.assertEqual(panel.axis_label("x"), "t (s)")
        values = [number(t.text) for t in panel.tick_labels("x")]
        self.assertEqual((values[0], values[-1]), (0.0, 5.0))
        self.assertTrue(is_one_two_five(values[1] - values[0]))

    def test_zero_initial_energy_falls_back_to_absolute_error_in_joules(self):
        root = render(pendulum_csv(lambda t: 0.002 * t))
        panel = Panel(root, "energy-panel")
        label = panel.axis_label("y")
        self.assertIn("(J)", label)
        self.assertIn("absolute", label)
        self.assertNotIn("relative", label)
        values = [number(t.text) for t in panel.tick_labels("y")]
        self.assertLessEqual(values[0], 0.0)
        self.assertGreaterEqual(values[-1], 0.01)
        self.assertIn("J", root.find(f".//{SVG}text[@class='max-error']").text)

    def test_constant_energy_still_gets_an_axis(self):
        panel = Panel(render(pendulum_csv(lambda t: 10.0)), "energy-panel")
        values = panel.tick_values("y")
        self.assertGreaterEqual(len(values), 2)
        self.assertLessEqual(values[0], 0.0)
        self.assertGreaterEqual(values[-1], 0.0)


class CommandLineTest(unittest.TestCase):

    def test_writes_an_svg_titled_with_the_csv_stem(self):
        with tempfile.TemporaryDirectory(prefix="gencoord-plot-") as folder:
            source, target = Path(folder, "swing.csv"), Path(folder, "swing.svg")
            source.write_text(pendulum_csv(lambda t: 10.0, steps=50))
            plot.main([str(source), str(target)])
            root = ET.parse(target).getroot()
        titles = [t.text for t in root.iter(f"{SVG}text") if t.get("class") == "title"]
        self.assertTrue(titles and all(t.startswith("swing:") for t in titles), titles)


if __name__ == "__main__":
    unittest.main()
