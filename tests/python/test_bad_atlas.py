# SPDX-License-Identifier: BSD-3-Clause
"""Bad atlases: charts that do not describe the same system are refused, naming the chart and
the line of its add_chart() call, and nothing is written."""

from __future__ import annotations

import unittest

from .support import MARK
from .test_bad_models import BadModelTest

CHART = """\
from gencoord import Model, cos, sin


def chart(name, mass=1, length=1, **kw):
    model = Model(dim=2, chart=name, **kw)
    theta = model.coordinate("theta", "angle (rad)")
    l = model.parameter("l", length, "length (m)")
    bob = model.particle("bob", mass=mass, position=[l * sin(theta), -l * cos(theta)])
    model.gravity([0, -9.81])
    return model


"""


class BadAtlasTest(BadModelTest):

    def test_chart_with_another_mass(self):
        self.expect_model_error("atlas_mass", CHART + (
            'model = chart("a")\n'
            'model.add_chart(chart("b", mass=2))  ' + MARK + "\n"),
            ["chart 'b'", "particles", "same particles"])

    def test_chart_with_another_parameter_default(self):
        self.expect_model_error("atlas_parameter", CHART + (
            'model = chart("a")\n'
            'model.add_chart(chart("b", length=2))  ' + MARK + "\n"),
            ["chart 'b'", "parameters"])

    def test_unnamed_chart(self):
        self.expect_model_error("atlas_unnamed", CHART + (
            'model = chart(None)\n'
            'model.add_chart(chart("b"))  ' + MARK + "\n"), ["needs a name"])

    def test_two_charts_of_one_name(self):
        self.expect_model_error("atlas_twice", CHART + (
            'model = chart("a")\n'
            'model.add_chart(chart("a"))  ' + MARK + "\n"), ["chart 'a'", "two charts"])

    def test_generalized_force_in_an_atlas(self):
        self.expect_model_error("atlas_torque", CHART + (
            'model = chart("a")\n'
            'other = chart("b")\n'
            'other.generalized_force(other.coordinates[0].symbol, 1.0)\n'
            'model.add_chart(other)  ' + MARK + "\n"), ["chart 'b'", "generalized forces"])


def load_tests(loader, tests, pattern):
    """Only this file's tests (not the inherited BadModelTest ones)."""
    suite = unittest.TestSuite()
    for name in loader.getTestCaseNames(BadAtlasTest):
        if name.startswith("test_") and name in BadAtlasTest.__dict__:
            suite.addTest(BadAtlasTest(name))
    return suite
