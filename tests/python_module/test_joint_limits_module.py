# SPDX-License-Identifier: BSD-3-Clause
"""The Python module of a model with a joint limit (limited_arm.py: a two-link arm whose elbow
is stopped at +-0.5 rad, its shoulder motor rated): the module lists the limits and ratings;
simulate keeps the elbow in its range, with or without an inputs argument, and the energy of
the conservative arm never rises (the stops are inelastic); with joint_limits=False the same
swing leaves the range.

Run by CTest (python_module_tests) with the built modules on PYTHONPATH.
"""

import importlib
import os
import unittest

import numpy as np

MODULE_DIR = os.environ.get("GENCOORD_TEST_MODULE_DIR", "")


@unittest.skipUnless(MODULE_DIR, "run through CTest: python_module_tests")
class JointLimitsModuleTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.arm = importlib.import_module("limited_arm")

    def test_the_module_lists_the_limits(self):
        self.assertEqual(self.arm.limit_names, ("elbow stop", "shoulder motor"))
        self.assertEqual(self.arm.limited_coordinates, (1, 0))
        self.assertEqual((self.arm.lower_limits[0], self.arm.upper_limits[0]), (-0.5, 0.5))
        self.assertEqual(self.arm.velocity_limits[0], np.inf)
        # the shoulder's motor is rated, its range open
        self.assertEqual(list(self.arm.effort_limits), [np.inf, 40.0])
        self.assertEqual((self.arm.lower_limits[1], self.arm.upper_limits[1]), (-np.inf, np.inf))

    def test_the_elbow_stays_on_its_stops_and_energy_never_rises(self):
        _, q, _, energy = self.arm.simulate(t_end=3.0, dt=1e-3)
        elbow = q[:, 1]
        self.assertEqual(elbow.min(), -0.5)  # it reaches the stop and is put back exactly on it
        self.assertLessEqual(elbow.max(), 0.5)
        self.assertLess(np.diff(energy).max(), 1e-9)
        self.assertLess(energy[-1], energy[0] - 0.1)  # the impacts took energy

    def test_without_limits_the_swing_leaves_the_range(self):
        _, q, _, energy = self.arm.simulate(t_end=3.0, dt=1e-3, joint_limits=False)
        self.assertGreater(np.abs(q[:, 1]).max(), 0.52)  # it swings to 0.55 rad
        self.assertLess(np.abs(energy - energy[0]).max(), 1e-6)  # RK4's own error

    def test_a_driven_arm_keeps_its_limits(self):
        def damping(t, q, v):
            return np.array([-8.0 * v[0]])
        _, q, _, _ = self.arm.simulate(t_end=2.0, dt=1e-3, inputs=damping)
        self.assertGreaterEqual(q[:, 1].min(), -0.5)
        self.assertLessEqual(q[:, 1].max(), 0.5)
        self.assertTrue(np.any(np.abs(q[:, 1]) == 0.5))


if __name__ == "__main__":
    unittest.main()
