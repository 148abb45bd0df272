# SPDX-License-Identifier: BSD-3-Clause
"""Generation-time analysis of where J = dX/dq loses rank (gencoord/checks/singularities.py)."""

import unittest

from gencoord.generate.load import load_model
from gencoord.checks.singularities import analyse_singularities

from .support import MODELS


def report_of(name: str, options: dict | None = None, chart: int = 0):
    model, _, _ = load_model(str(MODELS / f"{name}.py"), options or {})
    return analyse_singularities([model, *model.charts][chart])


class SingularityAnalysisTest(unittest.TestCase):
    def test_spherical_pendulum_poles_from_the_factored_determinant(self):
        report = report_of("spherical_pendulum")
        self.assertEqual(report.singular_sets, ["sin(theta) = 0"], report.lines())
        self.assertIn("det(J^T J)", report.method)
        # random sampling alone gets close to a pole at some sample
        self.assertLess(report.worst_ratio, 0.05, report.lines())

    def test_zyx_euler_angles_pitch_singularity(self):
        report = report_of("rigid_body_euler")
        self.assertEqual(report.singular_sets, ["cos(pitch) = 0"], report.lines())

    def test_the_atlas_charts_have_their_own_singular_sets(self):
        self.assertEqual(report_of("spherical_pendulum", chart=1).singular_sets,
                         ["sin(alpha) = 0"])
        self.assertEqual(report_of("rigid_body_euler", chart=1).singular_sets,
                         ["cos(attitude) = 0"])

    def test_redundancy_of_spherical_coordinates_and_euler_angles(self):
        # (theta, phi) and (-theta, phi + pi) put the bob in the same place
        for name in ("spherical_pendulum", "rigid_body_euler", "spring_pendulum"):
            with self.subTest(model=name):
                report = report_of(name)
                self.assertIsNotNone(report.redundancy, report.lines())
                self.assertIn("same positions", report.redundancy)

    def test_polar_coordinates_are_singular_at_the_origin(self):
        self.assertEqual(report_of("spring_pendulum").singular_sets, ["r = 0"])

    def test_regular_parameterizations_report_none(self):
        # the double pendulum's det(J^T J) has a factor cos(2 theta1 - 2 theta2) - 3 that
        # never vanishes: it must not be reported
        for name, options in (("double_pendulum", {}), ("pendulum", {}), ("cart_pole", {}),
                              ("n_link_chain", {"n": "5"})):
            with self.subTest(model=name):
                report = report_of(name, options)
                self.assertEqual(report.singular_sets, [], report.lines())
                self.assertGreater(report.worst_ratio, 1e-3, report.lines())
                self.assertIsNone(report.redundancy, report.lines())

    def test_report_goes_into_the_header(self):
        text = (MODELS.parent / "generated" / "spherical_pendulum.hpp").read_text()
        self.assertIn("Singular configurations (J loses rank): sin(theta) = 0", text)
        self.assertIn("Singular configurations (J loses rank): sin(alpha) = 0", text)
        self.assertIn("Redundancy (warning): distinct coordinates give the same positions", text)


if __name__ == "__main__":
    unittest.main()
