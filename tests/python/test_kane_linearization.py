# SPDX-License-Identifier: BSD-3-Clause
"""The Kane reference linearization (tests/python_module/kane_linearization.py) against the
cart-pole's closed forms and central finite differences of its own nonlinear right-hand side."""

from __future__ import annotations

import math
import random
import unittest

from tests.python_module.kane_linearization import linearization, nonlinear_rhs, parameter_names

CLOSED_FORM_TOLERANCE = 1e-12
DIFFERENCE_TOLERANCE = 1e-6
STEP = 1e-5  # central differences: truncation ~STEP**2, round-off ~1e-16 / STEP


def random_parameters(system: str, rng: random.Random) -> dict:
    """Lengths and masses in [0.3, 2], g near 9.81: nothing degenerate."""
    params = {name: rng.uniform(0.3, 2.0) for name in parameter_names(system)}
    params["g"] = rng.uniform(9.0, 10.0)
    return params


def random_point(size: int, rng: random.Random):
    """q, v and F well away from equilibrium (v and F of order one)."""
    q = [rng.uniform(-1.5, 1.5) for _ in range(size)]
    v = [rng.choice((-1, 1)) * rng.uniform(0.5, 2.0) for _ in range(size)]
    return q, v, rng.uniform(-3.0, 3.0)


def cart_pole_accelerations(theta, theta_dot, F, l, m_cart, m_pole, g):
    """(s'', theta'') by hand from the Lagrangian of a cart and a point-mass pole tip:
        L = (m_cart + m_pole) s'^2 / 2 + m_pole l s' theta' cos(theta) + m_pole l^2 theta'^2 / 2
            - m_pole g l cos(theta)
    gives l theta'' + cos(theta) s'' = g sin(theta), and eliminating theta'' from the s equation
        (m_cart + m_pole sin^2) s'' = F + m_pole sin(theta) (l theta'^2 - g cos(theta))."""
    sin, cos = math.sin(theta), math.cos(theta)
    s_ddot = (F + m_pole * sin * (l * theta_dot ** 2 - g * cos)) / (m_cart + m_pole * sin ** 2)
    return s_ddot, (g * sin - cos * s_ddot) / l


class KaneLinearizationTest(unittest.TestCase):
    def assert_close(self, actual, expected, tolerance, what):
        """Entrywise, relative to max(1, |expected|)."""
        self.assertEqual(len(actual), len(expected), what)
        for k, (a, e) in enumerate(zip(actual, expected)):
            self.assertLessEqual(abs(a - e), tolerance * max(1.0, abs(e)),
                                 f"{what}[{k}]: {a!r} != {e!r}")

    def test_cart_pole_upright_matches_closed_form(self):
        # Linearizing the accelerations above at theta = theta' = F = 0, with M = m_cart + m_pole:
        #   s''     = (F - m_pole g theta) / m_cart
        #   theta'' = (M g theta - F) / (m_cart l)
        params = dict(l=0.8, m_cart=1.7, m_pole=0.35, g=9.81)
        l, m_cart, m_pole, g = (params[k] for k in ("l", "m_cart", "m_pole", "g"))
        A, B = linearization("cart_pole", [0.0, 0.0], [0.0, 0.0], 0.0, params)
        expected_A = [[0, 0, 1, 0],
                      [0, 0, 0, 1],
                      [0, -m_pole * g / m_cart, 0, 0],
                      [0, (m_cart + m_pole) * g / (m_cart * l), 0, 0]]
        self.assertEqual(len(A), 4)
        for row, (actual, expected) in enumerate(zip(A, expected_A)):
            self.assert_close(actual, expected, CLOSED_FORM_TOLERANCE, f"A[{row}]")
        self.assert_close([b for (b,) in B], [0, 0, 1 / m_cart, -1 / (m_cart * l)],
                          CLOSED_FORM_TOLERANCE, "B")

    def test_cart_pole_rhs_matches_lagrange(self):
        rng = random.Random(20240611)
        for trial in range(5):
            params = random_parameters("cart_pole", rng)
            q, v, F = random_point(2, rng)
            expected = v + list(cart_pole_accelerations(q[1], v[1], F, **params))
            self.assert_close(nonlinear_rhs("cart_pole", q, v, F, params), expected,
                              CLOSED_FORM_TOLERANCE, f"trial {trial}: rhs")

    def test_jacobians_match_central_differences(self):
        rng = random.Random(7)
        for system, n in (("cart_pole", 2), ("double_pendulum_on_cart", 3)):
            for trial in range(3):
                with self.subTest(system=system, trial=trial):
                    params = random_parameters(system, rng)
                    q, v, F = random_point(n, rng)
                    self.check_against_differences(system, n, q, v, F, params)

    def check_against_differences(self, system, n, q, v, F, params):
        A, B = linearization(system, q, v, F, params)
        self.assertEqual((len(A), len(A[0]), len(B), len(B[0])), (2 * n, 2 * n, 2 * n, 1))
        # Not an equilibrium, so A's acceleration rows carry the velocity and udot terms.
        self.assertGreater(max(abs(a) for a in nonlinear_rhs(system, q, v, F, params)[n:]),
                           0.1)

        def rhs(x, force):
            return nonlinear_rhs(system, x[:n], x[n:], force, params)

        x = q + v
        for j in range(2 * n):
            plus, minus = list(x), list(x)
            plus[j] += STEP
            minus[j] -= STEP
            column = [(a - b) / (2 * STEP) for a, b in zip(rhs(plus, F), rhs(minus, F))]
            self.assert_close([row[j] for row in A], column, DIFFERENCE_TOLERANCE,
                              f"A[:, {j}]")
        column = [(a - b) / (2 * STEP) for a, b in zip(rhs(x, F + STEP), rhs(x, F - STEP))]
        self.assert_close([b for (b,) in B], column, DIFFERENCE_TOLERANCE, "B")

    def test_bad_arguments_are_refused(self):
        params = dict(l=1.0, m_cart=1.0, m_pole=1.0, g=9.81)
        with self.assertRaises(ValueError):
            linearization("no_such_system", [0, 0], [0, 0], 0, params)
        with self.assertRaises(ValueError):
            linearization("cart_pole", [0, 0, 0], [0, 0], 0, params)
        with self.assertRaises(ValueError):
            nonlinear_rhs("cart_pole", [0, 0], [0, 0], 0, dict(params, l1=1.0))


if __name__ == "__main__":
    unittest.main()
