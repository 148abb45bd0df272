# SPDX-License-Identifier: BSD-3-Clause
"""Control inputs and linearization from the models' Python modules: linearize() against an
independent Kane derivation (kane_linearization.py) and finite differences, u= against the
inputs held in Params, simulate(inputs=...) as an input script and as an LQR feedback law.

Run by CTest (python_module_tests) with the built modules on PYTHONPATH.
"""

import importlib
import os
import unittest

import numpy as np
from scipy.linalg import solve_continuous_are

from tests.python_module.kane_linearization import linearization

MODULE_DIR = os.environ.get("GENCOORD_TEST_MODULE_DIR", "")
CARTS = ("cart_pole", "double_pendulum_on_cart")


def load(name):
    return importlib.import_module(name)


def params_dict(model, params):
    return {name: getattr(params, name) for name in model.parameter_names
            if name not in model.input_names}


def lqr_gain(A, B, q_weight=10.0, r_weight=1.0):
    X = solve_continuous_are(A, B, q_weight * np.eye(len(A)), r_weight * np.eye(B.shape[1]))
    return np.linalg.solve(r_weight * np.eye(B.shape[1]), B.T @ X)


@unittest.skipUnless(MODULE_DIR, "run through CTest: python_module_tests")
class ControlTest(unittest.TestCase):

    def test_linearize_equals_kanes_method(self):
        rng = np.random.default_rng(5)
        for name in CARTS:
            model = load(name)
            params = model.Params()
            points = [(np.zeros(model.nq), np.zeros(model.nq), 0.0)]
            points += [(0.5 * rng.standard_normal(model.nq), rng.standard_normal(model.nq),
                        rng.standard_normal()) for _ in range(3)]
            for q, v, u in points:
                A, B = model.linearize(q, v, u=u)
                A_kane, B_kane = linearization(name, q.tolist(), v.tolist(), u,
                                               params_dict(model, params))
                np.testing.assert_allclose(A, A_kane, rtol=1e-10, atol=1e-10, err_msg=name)
                np.testing.assert_allclose(B, B_kane, rtol=1e-10, atol=1e-10, err_msg=name)

    def test_linearize_equals_finite_differences(self):
        rng = np.random.default_rng(6)
        for name in CARTS:
            model = load(name)
            q, v = 0.5 * rng.standard_normal(model.nq), rng.standard_normal(model.nq)
            A, B = model.linearize(q, v, u=1.3, t=0.2)
            A_fd, B_fd = model.linearize(q, v, u=1.3, t=0.2, method="finite_difference")
            scale = np.abs(A).max()
            np.testing.assert_allclose(A, A_fd, rtol=0, atol=1e-7 * scale)
            np.testing.assert_allclose(B, B_fd, rtol=0, atol=1e-7 * np.abs(B).max())
            self.assertEqual(A.shape, (2 * model.nq, 2 * model.nq))
            self.assertEqual(B.shape, (2 * model.nq, model.num_inputs))

    def test_dynamics_derivatives_are_kanes_and_finite_differences(self):
        # the carts are small, derived densely; the 10-link chain's derivatives come from its
        # Newton-Euler recursion, differentiated
        rng = np.random.default_rng(8)
        for name in (*CARTS, "n_link_chain_10"):
            model = load(name)
            q, v = 0.5 * rng.standard_normal(model.nq), rng.standard_normal(model.nq)
            a, a_q, a_v, a_tau = model.dynamics_derivatives(q, v)
            np.testing.assert_allclose(a, model.qddot(q, v), rtol=1e-12, atol=1e-12)
            np.testing.assert_allclose(a_tau @ model.mass_matrix(q), np.eye(model.nq),
                                       atol=1e-10, err_msg=name)
            for j in range(model.nq):
                e = 1e-6 * np.eye(model.nq)[j]
                np.testing.assert_allclose(
                    a_q[:, j], (model.qddot(q + e, v) - model.qddot(q - e, v)) / 2e-6,
                    rtol=1e-6, atol=1e-6, err_msg=f"{name}: da/dq, column {j}")
                np.testing.assert_allclose(
                    a_v[:, j], (model.qddot(q, v + e) - model.qddot(q, v - e)) / 2e-6,
                    rtol=1e-6, atol=1e-6, err_msg=f"{name}: da/dv, column {j}")
            if name in CARTS:
                A_kane, _ = linearization(name, q.tolist(), v.tolist(), 0.0,
                                          params_dict(model, model.Params()))
                n = model.nq
                np.testing.assert_allclose(np.hstack([a_q, a_v]), A_kane[n:], rtol=1e-10,
                                           atol=1e-10, err_msg=name)
            qs, vs = rng.standard_normal((4, model.nq)), rng.standard_normal((4, model.nq))
            batch = model.dynamics_derivatives(qs, vs, threads=2)
            for k in range(4):
                for part, single in zip(batch, model.dynamics_derivatives(qs[k], vs[k])):
                    np.testing.assert_array_equal(part[k], single)

    def test_u_overrides_the_inputs_that_params_hold(self):
        model = load("double_pendulum_on_cart")
        rng = np.random.default_rng(7)
        q, v = rng.standard_normal((4, 3)), rng.standard_normal((4, 3))
        u = rng.standard_normal((4, 1))
        batch = model.qddot(q, v, u=u, threads=2)
        for i in range(4):
            held = model.qddot(q[i], v[i], params=model.Params(u=u[i, 0]))
            np.testing.assert_array_equal(batch[i], held)
            np.testing.assert_array_equal(model.qddot(q[i], v[i], u=float(u[i, 0])), held)
        # Ft = B u + the rest, and B is what input_matrix says
        f0 = model.applied_forces(q[0], v[0])
        f1 = model.applied_forces(q[0], v[0], u=2.0)
        np.testing.assert_allclose(f1 - f0, 2.0 * model.input_matrix(q[0], v[0])[:, 0],
                                   rtol=1e-14, atol=1e-14)

    def test_an_input_script_equals_the_input_held_in_params(self):
        model = load("cart_pole")
        held = model.simulate([0, 0.2], [0, 0], t_end=1.0, params=model.Params(u=0.3))
        scripted = model.simulate([0, 0.2], [0, 0], t_end=1.0, inputs={"u": lambda t: 0.3})
        for a, b in zip(held, scripted):
            np.testing.assert_array_equal(a, b)
        # keyframes through a spline: 0.3 up to round-off
        keyframed = model.simulate([0, 0.2], [0, 0], t_end=1.0,
                                   inputs={0: ([0.0, 0.5, 1.0], [0.3, 0.3, 0.3])})
        for a, b in zip(held, keyframed):
            np.testing.assert_allclose(a, b, rtol=1e-13, atol=1e-15)
        # a force that changes with time changes the motion
        pushed = model.simulate([0, 0.2], [0, 0], t_end=1.0, inputs={"u": lambda t: t})
        self.assertGreater(abs(pushed[1][-1, 0] - held[1][-1, 0]), 1e-3)

    def test_lqr_stabilizes_the_upright_poles(self):
        for name in CARTS:
            model = load(name)
            A, B = model.linearize(np.zeros(model.nq), np.zeros(model.nq))
            K = lqr_gain(A, B)
            q0 = np.zeros(model.nq)
            q0[1] = 0.2
            law = lambda t, q, v: -K @ np.concatenate([q, v])  # noqa: E731
            for integrator in ("rk4", "backward_euler"):
                t, q, v, _ = model.simulate(q0, np.zeros(model.nq), t_end=10.0, dt=1e-3,
                                            integrator=integrator, inputs=law, every=100)
                self.assertLess(np.abs(q[-1]).max(), 1e-3, f"{name}, {integrator}")
                self.assertLess(np.abs(v[-1]).max(), 1e-3, f"{name}, {integrator}")
            # without the controller the poles fall
            _, q, _, _ = model.simulate(q0, np.zeros(model.nq), t_end=2.0)
            self.assertGreater(np.abs(q[-1, 1:]).max(), 1.0)

    def test_bad_inputs_are_refused_with_a_clear_error(self):
        model = load("cart_pole")
        q, v = np.zeros(2), np.zeros(2)
        cases = [
            (lambda: model.qddot(q, v, u=[1.0, 2.0]), "u: expected"),
            (lambda: model.qddot(np.zeros((3, 2)), np.zeros((3, 2)), u=np.zeros((2, 1))),
             "u: expected one input vector"),
            (lambda: model.simulate(q, v, t_end=0.1, inputs={"F": lambda t: 0.0}),
             "has no input 'F'; its inputs are u"),
            (lambda: model.simulate(q, v, t_end=0.1, inputs=lambda t, q, v: [1.0, 2.0]),
             "expected 1 input values, got 2"),
            (lambda: model.simulate(q, v, t_end=0.1, inputs={"u": lambda t: 0.0},
                                    scripted={"s": lambda t: (0.0, 0.0, 0.0)}),
             "cannot be combined"),
            (lambda: model.linearize(q, v, method="exact"), "method: expected"),
            (lambda: load("double_pendulum").simulate(t_end=0.1, inputs=lambda t, q, v: []),
             "declares no inputs"),
        ]
        for call, message in cases:
            with self.assertRaises(ValueError) as caught:
                call()
            self.assertIn(message, str(caught.exception))
        free = load("double_pendulum")
        self.assertEqual((free.num_inputs, free.input_names), (0, ()))
        with self.assertRaises(TypeError):
            free.qddot(np.zeros(2), np.zeros(2), u=1.0)


if __name__ == "__main__":
    unittest.main()
