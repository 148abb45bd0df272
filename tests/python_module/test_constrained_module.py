# SPDX-License-Identifier: BSD-3-Clause
"""The Python modules of models with kinematic constraints (the four-bar, the slider-crank):
the constraint kernels, the constrained acceleration and its multipliers against the KKT
equations they solve, rhs and simulate on the constraints (projected, or held by Baumgarte's
feedback), inverse dynamics against forward dynamics, and linearize_constrained against the
slider-crank's small oscillation about its hanging pose in closed form.

Run by CTest (python_module_tests) with the built modules on PYTHONPATH.
"""

import importlib
import os
import unittest

import numpy as np

MODULE_DIR = os.environ.get("GENCOORD_TEST_MODULE_DIR", "")


@unittest.skipUnless(MODULE_DIR, "run through CTest: python_module_tests")
class ConstrainedModuleTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.four_bar = importlib.import_module("four_bar")
        cls.slider_crank = importlib.import_module("slider_crank")

    def state_on_the_loop(self, model, seed):
        rng = np.random.default_rng(seed)
        q = model.initial_q + 0.05 * rng.standard_normal(model.nq)
        v = rng.standard_normal(model.nq)
        return model.project(q, v)

    def test_metadata_names_the_constraints(self):
        self.assertEqual(self.four_bar.num_constraints, 2)
        self.assertEqual(self.four_bar.num_holonomic_constraints, 2)
        self.assertEqual(self.four_bar.constraint_names, ("loop_C_x", "loop_C_y"))
        self.assertFalse(hasattr(self.four_bar, "linearize"))  # linearize_constrained instead

    def test_project_puts_the_state_on_the_constraints(self):
        for seed in range(5):
            q, v = self.state_on_the_loop(self.four_bar, seed)
            self.assertLess(np.abs(self.four_bar.holonomic_constraints(q)).max(), 1e-13)
            self.assertLess(np.abs(self.four_bar.constraint_velocities(q, v)).max(), 1e-13)
            # the holonomic Jacobian is the constraint Jacobian of a model without rolling
            np.testing.assert_allclose(self.four_bar.holonomic_jacobian(q),
                                       self.four_bar.constraint_jacobian(q), atol=1e-15)

    def test_acceleration_and_multipliers_solve_the_kkt_equations(self):
        model = self.four_bar
        params = model.Params()
        params.u = 0.8
        for seed in range(5):
            q, v = self.state_on_the_loop(model, seed)
            a = model.constrained_qddot(q, v, params=params)
            lam = model.constraint_forces(q, v, params=params)
            A = model.constraint_jacobian(q, params=params)
            residual = (model.mass_matrix(q, params=params) @ a - model.forces(q, v, params=params)
                        - A.T @ lam)
            self.assertLess(np.abs(residual).max(), 1e-12)
            self.assertLess(np.abs(A @ a + model.constraint_bias(q, v, params=params)).max(),
                            1e-12)
            # the tree's qddot (loops open) is not the constrained one
            self.assertGreater(np.abs(model.qddot(q, v, params=params) - a).max(), 1e-3)
            np.testing.assert_array_equal(model.rhs(0.0, np.concatenate([q, v]), params),
                                          np.concatenate([v, a]))

    def test_simulate_starts_on_the_constraints_and_stays_there(self):
        model = self.four_bar
        q0 = model.initial_q + 0.01  # off the loop: simulate projects it first
        t, q, v, energy = model.simulate(q0, [3.0, 0.0, 0.0], t_end=5.0, dt=1e-3)
        worst = max(np.abs(model.holonomic_constraints(q[k])).max() for k in range(0, len(t), 50))
        self.assertLess(worst, 1e-12)
        self.assertLess(np.abs(model.constraint_velocities(q[-1], v[-1])).max(), 1e-12)
        self.assertLess(abs(energy[-1] - energy[0]) / abs(energy[0]), 1e-8)
        with self.assertRaisesRegex(ValueError, "kinematic constraints"):
            model.simulate(t_end=0.01, inputs={"u": lambda t: 1.0})

    def test_baumgarte_keeps_the_loop_near_closed_without_projection(self):
        model = self.four_bar
        t, q, v, energy = model.simulate(None, [3.0, 0.0, 0.0], t_end=2.0, dt=1e-3,
                                         baumgarte=20.0)
        gaps = [np.abs(model.holonomic_constraints(q[k])).max() for k in range(len(t))]
        self.assertLess(max(gaps), 1e-7)  # held near, not at round-off: no projection
        self.assertGreater(max(gaps), 1e-13)
        with self.assertRaisesRegex(ValueError, "baumgarte: expected a rate >= 0"):
            model.simulate(t_end=0.01, baumgarte=-1.0)

    def test_inverse_dynamics_gives_the_torque_that_forward_dynamics_turns_back(self):
        model = self.four_bar
        params = model.Params()
        for seed in range(3):
            q, v = self.state_on_the_loop(model, seed)
            u, lam, vdot = model.inverse_dynamics_constrained(q, v, [0], [2.5], params=params)
            self.assertEqual(u.shape, (1,))
            self.assertAlmostEqual(vdot[0], 2.5, places=10)
            params.u = u[0]
            np.testing.assert_allclose(model.constrained_qddot(q, v, params=params), vdot,
                                       rtol=1e-10, atol=1e-10)
            np.testing.assert_allclose(model.constraint_forces(q, v, params=params), lam,
                                       rtol=1e-10, atol=1e-10)
        with self.assertRaisesRegex(ValueError, "independent"):
            model.inverse_dynamics_constrained(q, v, [0, 1], [0.0, 0.0])
        # the slider-crank has two inputs for one degree of freedom: no unique answer
        self.assertFalse(hasattr(self.slider_crank, "inverse_dynamics_constrained"))

    def test_linearize_constrained_gives_the_slider_cranks_small_oscillation(self):
        # hanging pose: crank straight down, the rod and the slider then move with the crank's
        # end (a theta' each), so I = a^2 (m_a / 3 + m_b + m_s); the crank's and the rod's
        # weights give the stiffness g a (m_a + m_b) / 2; the slider force p acts through
        # ds/dcrank = a
        model = self.slider_crank
        p = model.Params()
        crank = -np.pi / 2
        rod = np.arcsin(p.a / p.b)
        q = [crank, rod, p.b * np.cos(rod)]
        A, B, zdot = model.linearize_constrained(q, [0.0, 0.0, 0.0], independent_q=[0],
                                                 dependent_q=[1, 2], independent_v=[0],
                                                 dependent_v=[1, 2], params=p)
        inertia = p.a**2 * (p.m_a / 3 + p.m_b + p.m_s)
        stiffness = p.g * p.a * (p.m_a + p.m_b) / 2
        np.testing.assert_allclose(zdot, [0.0, 0.0], atol=1e-9)
        np.testing.assert_allclose(A, [[0.0, 1.0], [-stiffness / inertia, 0.0]], rtol=1e-8,
                                   atol=1e-8)
        np.testing.assert_allclose(B, [[0.0, 0.0], [1 / inertia, p.a / inertia]], rtol=1e-8,
                                   atol=1e-8)
        with self.assertRaisesRegex(ValueError, "dependent coordinates"):
            model.linearize_constrained(q, [0.0] * 3, [0], [1], [0], [1, 2])


if __name__ == "__main__":
    unittest.main()
