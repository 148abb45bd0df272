# SPDX-License-Identifier: BSD-3-Clause
"""forces_have_potential: which models' applied forces at rest are -dV/dq (the flag the model
tests read instead of model names); conserves_energy: which models keep E = T + V (the plots
call E - E0 an error for them and the energy's change for the others)."""

from __future__ import annotations

import unittest

from gencoord import Model, cos, sin
from gencoord.checks.conservative import conserves_energy, forces_have_potential
from gencoord.generate.load import load_model

from .support import MODELS


def pendulum(moving_pivot=False):
    """A pendulum under gravity, its pivot at rest or moving up and down with t."""
    model = Model(dim=2)
    pivot_height = sin(model.t) if moving_pivot else 0
    theta = model.coordinate("theta", "angle (rad)")
    c = model.parameter("c", 0.1, "damping (N s/m)")
    pivot = model.fixed_point("pivot", [0, pivot_height])
    bob = model.particle("bob", mass=1, position=[sin(theta), pivot_height - cos(theta)])
    model.gravity([0, -9.81])
    return model, theta, c, pivot, bob


class ForcesHavePotentialTest(unittest.TestCase):

    def test_built_in_models(self):
        for stem, expected in [("pendulum", True), ("cart_pole", False),
                               ("bead_on_rotating_hoop", True), ("kapitza_pendulum", True)]:
            with self.subTest(stem):
                model, _, _ = load_model(str(MODELS / f"{stem}.py"))
                self.assertIs(forces_have_potential(model), expected)

    def test_damper_to_a_fixed_pivot_is_idle_at_rest(self):
        model, _, c, pivot, bob = pendulum()
        model.damper(pivot, bob, c)
        self.assertTrue(forces_have_potential(model))

    def test_damper_to_a_moving_pivot_acts_at_rest(self):
        model, _, c, pivot, bob = pendulum(moving_pivot=True)
        model.damper(pivot, bob, c)
        self.assertFalse(forces_have_potential(model))

    def test_user_forces(self):
        model, theta, c, _, bob = pendulum()
        model.force(bob, [-c * bob.xdot[0], 0])  # drag: zero at rest
        model.generalized_force(theta, -c * model.rate(theta))
        self.assertTrue(forces_have_potential(model))
        model.force(bob, [c, 0], potential=-c * bob.x[0])  # conservative, declared so
        self.assertTrue(forces_have_potential(model))
        model.force(bob, [c, 0])  # the same force without its potential
        self.assertFalse(forces_have_potential(model))


if __name__ == "__main__":
    unittest.main()


class ConservesEnergyTest(unittest.TestCase):

    def test_built_in_models(self):
        # the cart-pole has an input, the Kapitza pendulum's pivot moves with t
        for stem, expected in [("pendulum", True), ("double_pendulum", True),
                               ("cart_pole", False), ("kapitza_pendulum", False)]:
            with self.subTest(stem):
                model, _, _ = load_model(str(MODELS / f"{stem}.py"))
                self.assertIs(conserves_energy(model), expected)

    def test_what_changes_the_energy(self):
        def damper(model, theta, c, pivot, bob):
            model.damper(pivot, bob, c)

        def damped_spring(model, theta, c, pivot, bob):
            model.spring(pivot, bob, 10.0, 1.0, damping=c)

        def joint_damping(model, theta, c, pivot, bob):
            model.joint_spring(theta, 1.0, damping=c)

        def force_without_potential(model, theta, c, pivot, bob):
            model.generalized_force(theta, -c * model.rate(theta))

        def limit(model, theta, c, pivot, bob):
            model.limit(theta, -0.5, 0.5)

        def spring_with_potential(model, theta, c, pivot, bob):
            model.spring(pivot, bob, 10.0, 1.0)

        for change, conserved in [(damper, False), (damped_spring, False),
                                  (joint_damping, False), (force_without_potential, False),
                                  (limit, False), (spring_with_potential, True)]:
            with self.subTest(change.__name__):
                model, *items = pendulum()
                change(model, *items)
                self.assertIs(conserves_energy(model), conserved)
        self.assertFalse(conserves_energy(pendulum(moving_pivot=True)[0]))
