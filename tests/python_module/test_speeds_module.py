# SPDX-License-Identifier: BSD-3-Clause
"""The Python module of a model with generalized speeds (floating_arm.py: a free trunk, a ball
arm and a motorized revolute hand; nq = 12, nv = 10), checked against independent NumPy
derivations: the quaternion kinematics, central differences of rhs, a linearization in local
coordinates whose rate uses the closed-form inverse of SO(3)'s right Jacobian (the module uses
its first-order term at delta = 0 only), SciPy's integrators, and the invariants of a force-free
motion: energy, momentum and unit quaternions.

Run by CTest (python_module_tests) with the built modules on PYTHONPATH.
"""

import importlib
import os
import unittest

import numpy as np

MODULE_DIR = os.environ.get("GENCOORD_TEST_MODULE_DIR", "")

TRUNK, ARM = slice(3, 7), slice(7, 11)  # the quaternions in q
LINEAR, OMEGA, ARM_OMEGA, HAND = slice(0, 3), slice(3, 6), slice(6, 9), 9  # the speeds


def product(a, b):
    """The quaternion product a (x) b, scalar first."""
    return np.array([a[0] * b[0] - a[1:] @ b[1:],
                     *(a[0] * b[1:] + b[0] * a[1:] + np.cross(a[1:], b[1:]))])


def exp(d):
    angle = np.linalg.norm(d)
    if angle == 0:
        return np.array([1.0, 0, 0, 0])
    return np.array([np.cos(angle / 2), *(np.sin(angle / 2) * d / angle)])


def rotation(quaternion):
    w, x, y, z = quaternion
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def cross_matrix(a):
    return np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])


def inverse_right_jacobian(d):
    """J_r(d)^-1 of SO(3) in closed form: omega = J_r(d) d' for R = R0 Exp(d)."""
    angle, cross = np.linalg.norm(d), cross_matrix(d)
    if angle < 1e-8:
        return np.eye(3) + cross / 2
    c = 1 / angle ** 2 - (1 + np.cos(angle)) / (2 * angle * np.sin(angle))
    return np.eye(3) + cross / 2 + c * cross @ cross


def retract(q0, delta):
    """floating_arm's local coordinates: the trunk's position along its body axes at q0, both
    quaternions turned about their own axes, the hand's angle added."""
    q = np.array(q0, dtype=float)
    q[0:3] += rotation(q0[TRUNK]) @ delta[LINEAR]
    q[TRUNK] = product(q0[TRUNK], exp(delta[OMEGA]))
    q[ARM] = product(q0[ARM], exp(delta[ARM_OMEGA]))
    q[11] += delta[HAND]
    return q


def local_rate(q0, delta, v):
    """delta' at (delta, v), exactly: q' = G(q) v written in the local coordinates."""
    q = retract(q0, delta)
    rate = np.empty(10)
    rate[LINEAR] = rotation(q0[TRUNK]).T @ rotation(q[TRUNK]) @ v[LINEAR]
    rate[OMEGA] = inverse_right_jacobian(delta[OMEGA]) @ v[OMEGA]
    rate[ARM_OMEGA] = inverse_right_jacobian(delta[ARM_OMEGA]) @ v[ARM_OMEGA]
    rate[HAND] = v[HAND]
    return rate


def central_differences(function, x, step):
    columns = []
    for j in range(len(x)):
        e = np.zeros(len(x))
        e[j] = step
        columns.append((function(x + e) - function(x - e)) / (2 * step))
    return np.column_stack(columns)


@unittest.skipUnless(MODULE_DIR, "run through CTest: python_module_tests")
class SpeedsModuleTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.m = importlib.import_module("floating_arm")
        rng = np.random.default_rng(7)
        cls.q = retract(np.array(cls.m.initial_q), rng.uniform(-1, 1, 10))
        cls.v = rng.uniform(-1, 1, 10)
        cls.weightless = cls.m.Params(g=0.0)

    def relative_error(self, a, b):
        return np.abs(np.asarray(a) - np.asarray(b)).max() / max(np.abs(b).max(), 1.0)

    def test_the_module_names_its_speeds_and_quaternions(self):
        self.assertEqual((self.m.nq, self.m.nv), (12, 10))
        self.assertEqual(self.m.quaternion_starts, (3, 7))
        self.assertEqual(self.m.speed_names[:4], ("trunk_vx", "trunk_vy", "trunk_vz", "trunk_wx"))
        self.assertEqual(self.m.speed_names[9], "hand_joint")
        self.assertEqual(self.m.initial_v.shape, (10,))

    def test_coordinate_rates_are_the_quaternion_kinematics(self):
        q, v = self.q, self.v
        rates = np.concatenate([rotation(q[TRUNK]) @ v[LINEAR],
                                product(q[TRUNK], np.array([0, *v[OMEGA]])) / 2,
                                product(q[ARM], np.array([0, *v[ARM_OMEGA]])) / 2, [v[HAND]]])
        self.assertLess(self.relative_error(self.m.coordinate_rates(q, v), rates), 1e-15)

    def test_kernels_take_nv_speeds_one_state_or_a_batch(self):
        m, q, v = self.m, self.q, self.v
        self.assertEqual(m.mass_matrix(q).shape, (10, 10))
        self.assertEqual(m.jacobian(q).shape, (m.nx, 10))
        self.assertEqual(m.residual_jacobians(q, v, v)[0].shape, (10, 12))
        # r(q, v, qddot) = 0, and J v = the particles' velocities
        self.assertLess(np.abs(m.inverse_dynamics(q, v, m.qddot(q, v))).max(), 1e-11)
        self.assertLess(self.relative_error(m.jacobian(q) @ v, m.velocities(q, v)), 1e-14)
        qs = np.array([retract(q, d) for d in np.random.default_rng(1).uniform(-1, 1, (5, 10))])
        vs = np.tile(v, (5, 1))
        batch = m.qddot(qs, vs, threads=2)
        for k in range(5):
            np.testing.assert_array_equal(batch[k], m.qddot(qs[k], vs[k]))
        # four states per call across SIMD lanes, and the fifth alone
        self.assertLess(self.relative_error(m.qddot_simd(qs, vs), batch), 1e-13)
        with self.assertRaisesRegex(ValueError, r"v: expected an array of shape \(10,\)"):
            m.qddot(q, np.zeros(12))

    def test_rhs_is_the_rates_and_accelerations_and_jac_its_derivative(self):
        m, q, v = self.m, self.q, self.v
        y = np.concatenate([q, v])
        np.testing.assert_array_equal(m.rhs(0.0, y), np.concatenate(
            [m.coordinate_rates(q, v), m.qddot(q, v)]))
        numeric = central_differences(lambda x: m.rhs(0.0, x), y, 1e-6)
        self.assertEqual(m.jac(0.0, y).shape, (22, 22))
        self.assertLess(self.relative_error(m.jac(0.0, y), numeric), 1e-8)

    def test_retract_and_local_coordinates_invert_each_other(self):
        m, q = self.m, self.q
        delta = np.random.default_rng(3).uniform(-1.5, 1.5, 10)
        moved = m.retract(q, delta)
        self.assertLess(self.relative_error(moved, retract(q, delta)), 1e-15)
        self.assertLess(self.relative_error(m.local_coordinates(q, moved), delta), 1e-14)
        # -q is the same rotation: the shorter turn again
        flipped = moved.copy()
        flipped[ARM] *= -1
        self.assertLess(self.relative_error(m.local_coordinates(q, flipped), delta), 1e-14)
        # d retract/d delta at 0 is G(q)
        rate_matrix = np.column_stack([m.coordinate_rates(q, e) for e in np.eye(10)])
        slope = central_differences(lambda d: m.retract(q, d), np.zeros(10), 1e-6)
        self.assertLess(self.relative_error(slope, rate_matrix), 1e-9)

    def test_linearize_in_local_coordinates_against_the_exact_local_rate(self):
        m, q, v = self.m, self.q, self.v
        u = np.array([0.3])

        def f(x):
            delta, speeds = x[:10], x[10:]
            return np.concatenate([local_rate(q, delta, speeds),
                                   m.qddot(retract(q, delta), speeds, u=u)])

        x0 = np.concatenate([np.zeros(10), v])
        np.testing.assert_allclose(f(x0)[:10], v, rtol=0, atol=1e-15)  # delta' = v at delta = 0
        A, B = m.linearize(q, v, u)
        self.assertEqual((A.shape, B.shape), ((20, 20), (20, 1)))
        self.assertLess(self.relative_error(A, central_differences(f, x0, 1e-6)), 1e-7)
        self.assertLess(self.relative_error(
            A, m.linearize(q, v, u, method="finite_difference")[0]), 1e-7)
        # dynamics_derivatives: da/dq in the embedding of q, which G(q) takes to delta
        _, a_q, a_v, a_tau = m.dynamics_derivatives(q, v, u=u)
        rate_matrix = np.column_stack([m.coordinate_rates(q, e) for e in np.eye(10)])
        self.assertEqual(a_q.shape, (10, 12))
        self.assertLess(self.relative_error(A[10:], np.hstack([a_q @ rate_matrix, a_v])), 1e-13)
        self.assertLess(self.relative_error(a_tau @ m.mass_matrix(q), np.eye(10)), 1e-12)
        # B = [0; Mt^-1 B(q)]
        np.testing.assert_array_equal(B[:10], 0)
        self.assertLess(self.relative_error(
            B[10:], np.linalg.solve(m.mass_matrix(q), m.input_matrix(q, v))), 1e-13)

    def test_at_rest_the_local_coordinates_rates_are_the_speeds(self):
        A, _ = self.m.linearize(self.q, np.zeros(10))
        np.testing.assert_array_equal(A[:10, :10], 0)
        self.assertLess(np.abs(A[:10, 10:] - np.eye(10)).max(), 1e-15)

    def test_a_force_free_motion_keeps_energy_momentum_and_unit_quaternions(self):
        m, p = self.m, self.weightless
        v0 = np.array([0.2, -0.1, 0.3, 1.0, -2.0, 1.5, 2.0, 0.5, -1.0, 3.0])
        _, q, v, energy = m.simulate(self.q, v0, t_end=2.0, dt=1e-3, params=p)
        self.assertLess(np.abs(energy - energy[0]).max() / energy[0], 1e-9)
        for kernel in (m.linear_momentum, m.angular_momentum):
            moments = kernel(q, v, params=p)
            self.assertLess(np.abs(moments - moments[0]).max(), 1e-9 * np.abs(moments[0]).max())
        for quaternion in (TRUNK, ARM):
            self.assertLess(np.abs(np.linalg.norm(q[:, quaternion], axis=1) - 1).max(), 1e-14)

    def test_simulate_follows_scipy_on_the_same_right_hand_side(self):
        from scipy.integrate import solve_ivp
        m, v0 = self.m, self.v
        t, q, v, _ = m.simulate(self.q, v0, t_end=1.0, dt=1e-3)
        y0 = np.concatenate([self.q, v0])
        tight = solve_ivp(m.rhs, (0, 1), y0, method="DOP853", rtol=1e-12, atol=1e-12)
        end = np.concatenate([q[-1], v[-1]])
        self.assertLess(self.relative_error(end, tight.y[:, -1]), 1e-9)
        stiff = solve_ivp(m.rhs, (0, 1), y0, method="Radau", jac=m.jac, rtol=1e-9, atol=1e-9)
        self.assertTrue(stiff.success)
        self.assertLess(self.relative_error(stiff.y[:, -1], tight.y[:, -1]), 1e-6)

    def test_a_feedback_law_on_the_speeds_takes_energy_out(self):
        m, p = self.m, self.weightless
        v0 = np.array([0, 0, 0, 0.5, 0, 0, 0, 1.0, 0, 2.0])
        for integrator in ("rk4", "backward_euler"):
            _, q, v, energy = m.simulate(self.q, v0, t_end=2.0, dt=1e-3, params=p,
                                         integrator=integrator,
                                         inputs=lambda t, q, v: np.array([-0.5 * v[9]]))
            self.assertLess(np.diff(energy).max(), 1e-12, integrator)  # P = u v_hand <= 0
            self.assertLess(energy[-1], 0.9 * energy[0], integrator)
            self.assertLess(np.abs(np.linalg.norm(q[:, ARM], axis=1) - 1).max(), 1e-14)

    def test_a_scripted_hand_follows_its_script_on_unit_quaternions(self):
        m = self.m
        hand = m.coordinate_names.index("hand_joint")
        t, q, v, _ = m.simulate(t_end=1.0, dt=1e-3, every=10, scripted={
            "hand_joint": lambda s: (0.4 * np.sin(3 * s), 1.2 * np.cos(3 * s),
                                     -3.6 * np.sin(3 * s))})
        np.testing.assert_allclose(q[:, hand], 0.4 * np.sin(3 * t), rtol=0, atol=1e-15)
        np.testing.assert_allclose(v[:, HAND], 1.2 * np.cos(3 * t), rtol=0, atol=1e-15)
        for part in (TRUNK, ARM):
            self.assertLess(np.abs(np.linalg.norm(q[:, part], axis=1) - 1).max(), 1e-14)
        self.assertGreater(np.abs(q[:, ARM] - q[0, ARM]).max(), 1e-2)  # the arm swings
        with self.assertRaisesRegex(ValueError, "scripted: coordinate 'trunk_x' of model "
                                                "'floating_arm' belongs to a free or ball joint"):
            m.simulate(t_end=0.1, scripted={"trunk_x": lambda s: (s, 1.0, 0.0)})


if __name__ == "__main__":
    unittest.main()
