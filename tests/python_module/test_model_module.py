# SPDX-License-Identifier: BSD-3-Clause
"""The models' Python modules (bindings/python) against the C++ kernels, SciPy's integrators,
finite differences and the runtime's own simulation.

Run by CTest (python_module_tests) with the built modules and kernel_reference_<model>
programs in $GENCOORD_TEST_MODULE_DIR, which is also on PYTHONPATH.
"""

import importlib
import os
import subprocess
import unittest

import numpy as np
from scipy.integrate import solve_ivp

MODULE_DIR = os.environ.get("GENCOORD_TEST_MODULE_DIR", "")
MODELS = [m for m in os.environ.get("GENCOORD_TEST_MODELS", "").split(",") if m]
KERNELS_Q = ("mass_matrix", "potential_energy", "generalized_potential_energy", "positions",
             "jacobian")
KERNELS_QV = ("applied_forces", "generalized_forces", "inertial_forces", "forces", "dynamics",
              "qddot", "kinetic_energy", "energy", "velocities", "bias_acceleration",
              "linear_momentum", "angular_momentum")
KERNELS_QVA = ("inverse_dynamics", "residual_jacobians")


def load(name):
    return importlib.import_module(name)


def random_states(model, count, seed):
    """(t, q, v, qdd) near the model file's initial state: away from any singular chart."""
    rng = np.random.default_rng(seed)
    q = model.initial_q + 0.3 * rng.standard_normal((count, model.nq))
    v = rng.standard_normal((count, model.nq))
    qdd = rng.standard_normal((count, model.nq))
    t = rng.uniform(0.0, 2.0, count)
    return t, q, v, qdd


def as_list(result):
    """A kernel's result (array, float or tuple of arrays) as {suffix: flat float list}."""
    if isinstance(result, tuple):
        return {f".{k}": np.ravel(r).tolist() for k, r in enumerate(result)}
    return {"": np.ravel(result).tolist()}


@unittest.skipUnless(MODULE_DIR and MODELS, "run through CTest: python_module_tests")
class ModuleTest(unittest.TestCase):

    def test_every_kernel_equals_the_cxx_kernel_bit_for_bit(self):
        for name in MODELS:
            model = load(name)
            t, q, v, qdd = random_states(model, 5, seed=1)
            lines = [" ".join(x.hex() for x in [t[i], *q[i], *v[i], *qdd[i]])
                     for i in range(len(t))]
            program = os.path.join(MODULE_DIR, f"kernel_reference_{name}")
            output = subprocess.run([program], input="\n".join(lines) + "\n", text=True,
                                    capture_output=True, check=True).stdout.splitlines()
            per_state = len(output) // len(t)
            for i in range(len(t)):
                expected = {}
                for line in output[i * per_state:(i + 1) * per_state]:
                    kernel, *values = line.split()
                    expected[kernel] = [float.fromhex(x) for x in values]
                got = {}
                for kernel in KERNELS_Q:
                    for suffix, values in as_list(getattr(model, kernel)(q[i], t=t[i])).items():
                        got[kernel + suffix] = values
                for kernel in KERNELS_QV:
                    result = getattr(model, kernel)(q[i], v[i], t[i])
                    for suffix, values in as_list(result).items():
                        got[kernel + suffix] = values
                for kernel in KERNELS_QVA:
                    result = getattr(model, kernel)(q[i], v[i], qdd[i], t[i])
                    for suffix, values in as_list(result).items():
                        got[kernel + suffix] = values
                got["fixed_point_positions"] = np.ravel(
                    model.fixed_point_positions(t[i])).tolist()
                if model.num_inputs:
                    u = 0.5 + np.arange(model.num_inputs)
                    got["input_matrix"] = np.ravel(
                        model.input_matrix(q[i], v[i], t[i], u=u)).tolist()
                    got["qddot_with_inputs"] = model.qddot(q[i], v[i], t[i], u=u).tolist()
                self.assertEqual(sorted(got), sorted(expected), name)
                for kernel, values in expected.items():
                    self.assertEqual(got[kernel], values, f"{name}.{kernel} at state {i}")

    def test_a_threaded_batch_equals_single_calls(self):
        for name in MODELS:
            model = load(name)
            t, q, v, qdd = random_states(model, 37, seed=2)
            params = [model.Params() for _ in t]
            for k, p in enumerate(params):
                setattr(p, model.parameter_names[0], 1.0 + 0.01 * k)
            for threads in (1, 3, 8):
                batch = model.qddot(q, v, t, params, threads=threads)
                mt, f = model.dynamics(q, v, t, threads=threads)
                energy = model.energy(q, v, 0.5, threads=threads)
                r_q, r_v = model.residual_jacobians(q, v, qdd, t, threads=threads)
                self.assertEqual(batch.shape, (37, model.nq))
                self.assertEqual(mt.shape, (37, model.nq, model.nq))
                for i in range(len(t)):
                    np.testing.assert_array_equal(batch[i], model.qddot(q[i], v[i], t[i],
                                                                        params[i]))
                    single_mt, single_f = model.dynamics(q[i], v[i], t[i])
                    np.testing.assert_array_equal(mt[i], single_mt)
                    np.testing.assert_array_equal(f[i], single_f)
                    self.assertEqual(energy[i], model.energy(q[i], v[i], 0.5))
                    single_r_q, single_r_v = model.residual_jacobians(q[i], v[i], qdd[i], t[i])
                    np.testing.assert_array_equal(r_q[i], single_r_q)
                    np.testing.assert_array_equal(r_v[i], single_r_v)

    def test_a_simd_batch_equals_single_calls_to_round_off(self):
        for name in MODELS:
            model = load(name)
            t, q, v, _ = random_states(model, 203, seed=3)  # 50 packs of 4 and a tail of 3
            params = model.Params()
            setattr(params, model.parameter_names[0], 1.1)
            single = np.array([model.qddot(q[i], v[i], t[i], params) for i in range(len(t))])
            scale = np.maximum(1.0, np.linalg.norm(single, axis=1))[:, None]
            for threads in (1, 3):
                packed = model.qddot_simd(q, v, t, params, threads=threads)
                self.assertEqual(packed.shape, single.shape)
                # measured 5e-16 to 2e-15, and 1.1e-13 for the heavy top, whose Euler angles
                # come near their singular chart (the C++ test's states give 6e-13)
                self.assertLess(np.max(np.abs(packed - single) / scale), 1e-11, name)
            np.testing.assert_array_equal(model.qddot_simd(q[0], v[0], t[0], params), single[0])

    def test_a_simd_batch_takes_one_parameter_set(self):
        model = load("cart_pole")
        t, q, v, _ = random_states(model, 9, seed=4)
        u = np.array([2.5])
        np.testing.assert_allclose(model.qddot_simd(q, v, t, u=u), model.qddot(q, v, t, u=u),
                                   rtol=1e-13, atol=1e-13)
        self.assertFalse(np.allclose(model.qddot_simd(q, v, t, u=u), model.qddot_simd(q, v, t)))
        for call in (lambda: model.qddot_simd(q, v, t, u=np.ones((9, 1))),
                     lambda: model.qddot_simd(q, v, t, [model.Params()] * 9)):
            with self.assertRaisesRegex(ValueError, "share one parameter set"):
                call()

    def test_a_simd_batch_is_nan_where_single_calls_are(self):
        # with m1 = 0 the double pendulum's Mt is singular where theta1 = theta2
        model = load("double_pendulum")
        params = model.Params(m1=0.0)
        t, q, v, _ = random_states(model, 23, seed=5)
        q[[2, 9, 10, 22], 1] = q[[2, 9, 10, 22], 0]
        single = np.array([model.qddot(q[i], v[i], t[i], params) for i in range(len(t))])
        packed = model.qddot_simd(q, v, t, params, threads=1)
        np.testing.assert_array_equal(np.isnan(packed), np.isnan(single))
        self.assertEqual(np.isnan(single).any(axis=1).sum(), 4)
        ok = ~np.isnan(single)
        np.testing.assert_allclose(packed[ok], single[ok], rtol=1e-12, atol=1e-12)

    def test_float32_and_lists_are_read_as_float64(self):
        model = load("double_pendulum")
        q, v = np.array([0.3, -0.2]), np.array([0.1, 0.5])
        single = model.qddot(q.astype(np.float32), v.astype(np.float32))
        np.testing.assert_array_equal(single, model.qddot(q.astype(np.float32).astype(float),
                                                          v.astype(np.float32).astype(float)))
        self.assertEqual(single.dtype, np.float64)
        np.testing.assert_array_equal(model.qddot([0.3, -0.2], [0.1, 0.5]), model.qddot(q, v))
        np.testing.assert_array_equal(model.qddot([0, 0], [0, 0]),
                                      model.qddot(np.zeros(2), np.zeros(2)))

    def test_bad_shapes_and_dtypes_name_the_argument(self):
        model = load("double_pendulum")
        q = np.zeros(2)
        cases = [
            (lambda: model.qddot(np.zeros(3), q), "q: expected an array of shape (2,) or (N, 2)"),
            (lambda: model.qddot(q, np.zeros((4, 2))), "v: expected the batch shape of q"),
            (lambda: model.qddot(np.zeros((4, 2)), np.zeros((4, 3))), "v: expected"),
            (lambda: model.qddot(q, q.astype(complex)), "v: expected an array of shape (2,)"),
            (lambda: model.qddot(q, ["a", "b"]), "got dtype"),
            (lambda: model.energy(q, q, np.zeros(3)), "t: expected a number"),
            (lambda: model.qddot(np.zeros((4, 2)), np.zeros((4, 2)), np.zeros(3)),
             "t: expected a number or an array of shape (4,)"),
            (lambda: model.qddot(q, q, params=3), "params: expected a double_pendulum.Params"),
            (lambda: model.qddot(np.zeros((2, 2)), np.zeros((2, 2)), params=[model.Params()]),
             "params: a batch of N = 2 states needs one Params or N of them"),
            (lambda: model.qddot(np.zeros((2, 2)), np.zeros((2, 2)), threads=0),
             "threads: expected 1 to"),
            (lambda: model.qddot(np.zeros((2, 2)), np.zeros((2, 2)), threads=100000),
             "threads: expected 1 to"),
            (lambda: model.Params(g=float("nan")), "g: expected a finite number, got nan"),
            (lambda: model.Params(g="abc"), "g: expected a number, got 'abc'"),
            (lambda: setattr(model.Params(), "l1", float("inf")),
             "l1: expected a finite number, got inf"),
            (lambda: model.rhs(0.0, np.zeros(3)), "y: expected an array of shape (4,)"),
            # a non-finite state is refused by every entry point alike, the raw kernels too
            (lambda: model.qddot([float("nan"), 0.0], q), "q[0] is nan: expected finite numbers"),
            (lambda: model.mass_matrix(np.array([[0.0, 0.0], [0.0, np.inf]])),
             "q[1, 1] is inf: expected finite numbers"),
            (lambda: model.energy(q, q, float("nan")), "t is nan: expected finite numbers"),
            (lambda: model.rhs(0.0, [0.0, 0.0, float("-inf"), 0.0]),
             "y[2] is -inf: expected finite numbers"),
            (lambda: model.simulate(q0=[0.0, float("nan")]), "q0[1] is nan"),
            (lambda: model.simulate(np.zeros(3)), "q0: expected"),
            (lambda: model.simulate(t_end=1.0, dt=0.3), "whole number of steps"),
            (lambda: model.simulate(integrator="rk5"), "unknown integrator 'rk5'"),
            (lambda: model.simulate(scripted={"theta9": lambda t: (0, 0, 0)}),
             "has no coordinate 'theta9'"),
        ]
        for call, message in cases:
            with self.assertRaises(ValueError) as raised:
                call()
            self.assertIn(message, str(raised.exception))
        with self.assertRaises(TypeError) as raised:
            model.Params(lenght=2.0)
        self.assertIn("no parameter called 'lenght'; the parameters are l1, l2, m1, m2, g",
                      str(raised.exception))

    def test_metadata_and_params(self):
        model = load("double_pendulum")
        self.assertEqual((model.name, model.nq, model.dim, model.nx), ("double_pendulum", 2, 2, 4))
        self.assertEqual(model.coordinate_names, ("theta1", "theta2"))
        self.assertEqual(model.parameter_names, ("l1", "l2", "m1", "m2", "g"))
        self.assertEqual(model.parameter_descriptions[4], "gravitational acceleration (m/s^2)")
        self.assertEqual(model.particle_names, ("bob1", "bob2"))
        self.assertIn("rk4", model.integrators)
        with self.assertRaises(ValueError):
            model.initial_q[0] = 1.0  # read-only
        p = model.Params(l1=2.0)
        self.assertEqual((p.l1, p.l2, p.g), (2.0, 1.0, 9.81))
        p.g = 0.0
        self.assertEqual(p.to_dict()["g"], 0.0)
        self.assertEqual(repr(model.Params(m2=3.0)),
                         "Params(l1=1.0, l2=1.0, m1=1.0, m2=3.0, g=9.81)")
        self.assertIn("gravitational acceleration", model.Params.g.__doc__)
        # parameters reach the kernels: no gravity, no acceleration at rest
        np.testing.assert_array_equal(model.qddot([0.4, 1.0], [0.0, 0.0], params=p), [0.0, 0.0])
        np.testing.assert_allclose(model.positions([0.0, 0.0], params=model.Params(l1=2.0)),
                                   [0.0, -2.0, 0.0, -3.0], atol=1e-15)

    def test_jac_is_the_finite_difference_jacobian_of_rhs(self):
        for name in MODELS:
            model = load(name)
            t, q, v, _ = random_states(model, 3, seed=3)
            for i in range(len(t)):
                y = np.concatenate([q[i], v[i]])
                jac = model.jac(t[i], y)
                numeric = np.empty_like(jac)
                for j in range(len(y)):
                    h = 1e-6 * max(1.0, abs(y[j]))
                    up, down = y.copy(), y.copy()
                    up[j] += h
                    down[j] -= h
                    numeric[:, j] = (model.rhs(t[i], up) - model.rhs(t[i], down)) / (2 * h)
                scale = max(1.0, np.abs(jac).max())
                np.testing.assert_allclose(jac, numeric, rtol=0, atol=1e-6 * scale,
                                           err_msg=name)

    def test_radau_with_the_generated_jacobian_follows_rk4(self):
        for name in ("double_pendulum", "cart_pole", "heavy_top"):
            model = load(name)
            t, q, v, energy = model.simulate(t_end=2.0, dt=1e-4, every=1000)
            y0 = np.concatenate([model.initial_q, model.initial_v])
            solution = solve_ivp(model.rhs, (0.0, 2.0), y0, method="Radau", jac=model.jac,
                                 t_eval=t, rtol=1e-10, atol=1e-10)
            self.assertTrue(solution.success, solution.message)
            self.assertGreater(solution.njev, 0)
            np.testing.assert_allclose(solution.y[:model.nq].T, q, atol=1e-7, err_msg=name)
            np.testing.assert_allclose(solution.y[model.nq:].T, v, atol=1e-6, err_msg=name)

    def test_simulate_records_what_the_kernels_say(self):
        model = load("double_pendulum")
        seen = []
        t, q, v, energy = model.simulate([0.5, 0.0], [0.0, 0.0], t_end=1.0, dt=1e-3, every=250,
                                         observer=lambda *state: seen.append(state))
        np.testing.assert_array_equal(t, [0.0, 0.25, 0.5, 0.75, 1.0])
        self.assertEqual(q.shape, (5, 2))
        np.testing.assert_array_equal(q[0], [0.5, 0.0])
        for k in range(5):
            self.assertEqual(energy[k], model.energy(q[k], v[k], t[k]))
            self.assertEqual(seen[k][0], t[k])
            np.testing.assert_array_equal(seen[k][1], q[k])
        self.assertLess(np.abs(energy - energy[0]).max(), 1e-9)
        # implicit integrators run through the generated residual Jacobians
        _, _, _, implicit = model.simulate(t_end=1.0, dt=1e-2, integrator="implicit_midpoint")
        self.assertLess(np.abs(implicit - implicit[0]).max(), 1e-2)

    def test_scripted_coordinates_follow_their_script(self):
        model = load("cart_pole")
        index = 0  # the cart
        times = np.linspace(0.0, 1.0, 11)
        t, q, v, _ = model.simulate(t_end=1.0, dt=1e-3, every=100,
                                    scripted={model.coordinate_names[index]:
                                              (times, 0.2 * np.sin(3 * times))})
        np.testing.assert_allclose(q[:, index], 0.2 * np.sin(3 * t), atol=1e-3)
        omega = 2.0
        t, q, v, _ = model.simulate(t_end=1.0, dt=1e-3, every=100, scripted={
            index: lambda s: (np.sin(omega * s), omega * np.cos(omega * s),
                              -omega ** 2 * np.sin(omega * s))})
        np.testing.assert_allclose(q[:, index], np.sin(omega * t), atol=1e-12)
        np.testing.assert_allclose(v[:, index], omega * np.cos(omega * t), atol=1e-12)
        self.assertGreater(np.abs(q[:, 1] - q[0, 1]).max(), 1e-3)  # the pole swings

    def test_singular_dynamics_raise_the_modules_error(self):
        model = load("double_pendulum")
        with self.assertRaises(model.DynamicsError):
            model.rhs(0.0, np.zeros(4), model.Params(m1=0.0, m2=0.0))
        self.assertTrue(issubclass(model.DynamicsError, RuntimeError))
        self.assertTrue(np.isnan(model.qddot(np.zeros(2), np.zeros(2),
                                             params=model.Params(m1=0.0, m2=0.0))).all())


if __name__ == "__main__":
    unittest.main()
