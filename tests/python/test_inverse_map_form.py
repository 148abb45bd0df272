# SPDX-License-Identifier: BSD-3-Clause
"""The J-form of the generator equals the inverse-map form of the equations of motion.

For an invertible parameterization with a closed-form inverse q = Q(x), the equations of
motion can be written
    qddot = dQ/dx M^-1 F + d2Q/dx2 : (J v v^T J^T),
while the generator solves Mt qddot = Ft + Fi with Mt = J^T M J. The spring pendulum is a
particle in polar coordinates, x = r (sin theta, -cos theta), so
    Q(x, y) = (sqrt(x^2 + y^2), atan2(x, -y)).
F (gravity, the strain spring f = k (|x| - L) / L towards the pivot, air drag -c_air xdot) is
written out here independently of the generator.
"""

from __future__ import annotations

import math
import random
import unittest

import mpmath
import sympy as sp

from gencoord.derive.dense import derive
from gencoord.generate.load import load_model

from .support import DIGITS, MODELS, format_numbers, lambdify_flat, relative_error

STATES = 24
TOLERANCE = 1e-12


def inverse_map_form():
    """qddot from the inverse map, as expressions of (r, theta, r_dot, theta_dot, params)."""
    r, theta, r_dot, theta_dot = sp.symbols("r theta r_dot theta_dot", real=True)
    k, L, m, g, c_air = sp.symbols("k L m g c_air", real=True)
    x, y = sp.symbols("x y", real=True)
    point = sp.Matrix([x, y])

    inverse = sp.Matrix([sp.sqrt(x**2 + y**2), sp.atan2(x, -y)])       # Q(x)
    dQ = inverse.jacobian(point)                                      # dQ/dx
    hessians = [sp.hessian(component, point) for component in inverse]  # d2Q/dx2

    X = sp.Matrix([r * sp.sin(theta), -r * sp.cos(theta)])
    J = X.jacobian([r, theta])
    xdot = J * sp.Matrix([r_dot, theta_dot])

    distance = sp.sqrt(x**2 + y**2)
    spring = -k * (distance - L) / L * point / distance
    force = m * sp.Matrix([0, -g]) + spring - c_air * xdot  # F(x, xdot), xdot = J v
    velocity_term = sp.Matrix([(xdot.T * H * xdot)[0, 0] for H in hessians])
    qddot = dQ * force / m + velocity_term
    at_X = {x: X[0], y: X[1]}
    return [r, theta, r_dot, theta_dot, k, L, m, g, c_air], qddot.xreplace(at_X)


class InverseMapFormTest(unittest.TestCase):

    def test_inverse_map_form_equals_the_j_form(self):
        model, name, _ = load_model(str(MODELS / "spring_pendulum.py"))
        derivation = derive(model)
        names = ([str(q) for q in derivation.q] + [str(v) for v in derivation.v]
                 + [str(p) for p in derivation.params])
        form_args, form = inverse_map_form()
        self.assertEqual(sorted(names), sorted(str(a) for a in form_args),
                         "spring_pendulum's coordinates/parameters changed; update this test")
        args = [*derivation.q, *derivation.v, *derivation.params, derivation.t]
        mass = lambdify_flat(args, derivation.mass_matrix)
        forces = lambdify_flat(args, derivation.applied_forces + derivation.inertial_forces)
        form_fn = lambdify_flat(form_args, form)
        nq = len(derivation.q)

        rng = random.Random("spring_pendulum inverse-map form")
        with mpmath.workdps(DIGITS):
            for state in range(STATES):
                values = {
                    "r": rng.uniform(0.2, 3.0), "theta": rng.uniform(-math.pi, math.pi),
                    "r_dot": rng.uniform(-3, 3), "theta_dot": rng.uniform(-4, 4),
                    "k": rng.uniform(1, 500), "L": rng.uniform(0.3, 2.0),
                    "m": rng.uniform(0.2, 5), "g": rng.uniform(1, 25),
                    "c_air": rng.uniform(0, 3)}
                point = [mpmath.mpf(values[n]) for n in names]
                time = mpmath.mpf(0)
                Mt = mpmath.matrix(nq, nq)
                for index, value in enumerate(mass(*point, time)):
                    Mt[index // nq, index % nq] = value
                rhs = mpmath.matrix(forces(*point, time))
                j_form = list(mpmath.lu_solve(Mt, rhs))
                by_inverse_map = form_fn(*[mpmath.mpf(values[str(a)]) for a in form_args])
                error = relative_error(j_form, by_inverse_map)
                self.assertLess(
                    error, TOLERANCE,
                    f"state {state} ({values}): Mt^-1 (Ft + Fi) = {format_numbers(j_form)} "
                    "but dQ/dx M^-1 F + d2Q/dx2 : (J v v^T J^T) = "
                    f"{format_numbers(by_inverse_map)}")

    def test_velocity_term_is_the_centripetal_and_coriolis_acceleration(self):
        """Closed form of the inverse-map form's second term in polar coordinates, symbolically:
        d2Q/dx2 : (xdot xdot^T) = (r theta_dot^2, -2 r_dot theta_dot / r) for r > 0."""
        args, form = inverse_map_form()
        r, theta, r_dot, theta_dot, k, L, m, g, c_air = args
        free_motion = form.subs({k: 0, g: 0, c_air: 0})
        positive_r = sp.Symbol("r", positive=True)
        simplified = sp.simplify(free_motion.subs(r, positive_r)).subs(positive_r, r)
        expected = sp.Matrix([r * theta_dot**2, -2 * r_dot * theta_dot / r])
        self.assertEqual(sp.simplify(simplified - expected), sp.zeros(2, 1),
                         f"velocity term {simplified.T} != {expected.T}")


if __name__ == "__main__":
    unittest.main()
