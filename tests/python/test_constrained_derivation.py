# SPDX-License-Identifier: BSD-3-Clause
"""The kinematic constraints' equations (derive/kinematic_constraints.py) and the constrained
dynamics they give, checked numerically in 30-digit arithmetic.

FiniteDifferenceTest: at seeded random states, central differences of the generated
expressions themselves (step 1e-10, so truncation and round-off are both near 1e-20):
    holonomic_jacobian = dC/dq,   A = d(A v + b)/dv,
    holonomic rows of A v + b = dC/dt along q' = v (i.e. C_q v + C_t),
    A a + gamma = d/dt (A v + b) along q' = v, v' = a.

FourBarKaneTest: the four-bar (models/four_bar.py) derived from scratch with
sympy.physics.mechanics, Kane's method with the crank angle independent and the coupler and
rocker angles dependent (loop closure as configuration constraints, its time derivative as
velocity constraints); nothing of gencoord/derive is reused. At seeded random states on the
loop, the accelerations of all three angles from the generated Mt, Ft + Fi, A, gamma through
the KKT system
    [Mt  -A^T] [a     ]   [Ft + Fi]
    [A    0  ] [lambda] = [-gamma ]
must agree with Kane's to 1e-12 relative.
"""

from __future__ import annotations

import math
import random
import unittest

import mpmath
import sympy as sp
from sympy.physics import mechanics as me

from gencoord.derive.dense import Kinematics, derive
from gencoord.derive.kinematic_constraints import derive_kinematic_constraints
from gencoord.generate.load import load_model

from .support import DIGITS, MODELS, REPO, format_numbers, lambdify_flat, relative_error

CONSTRAINED = REPO / "tests" / "constrained"

STEP = mpmath.mpf("1e-10")          # central differences: error ~ STEP^2 and 10^-DIGITS/STEP
FD_TOLERANCE = mpmath.mpf("1e-16")  # far above those ~1e-20, far below any real error
FD_STATES = 8
KANE_STATES = 16
KANE_TOLERANCE = 1e-12
t = me.dynamicsymbols._t


class Constrained:
    """A model's generated equations as mpmath functions of (q, v, params, t), each returning
    its matrix's entries row major."""

    def __init__(self, path):
        model, self.name, _ = load_model(str(path))
        kin = Kinematics(model)
        derivation = derive(model, kin)
        constraints = derive_kinematic_constraints(model, kin)
        if constraints is None:
            raise AssertionError(f"{self.name}: declares no kinematic constraints")
        self.model, self.derivation, self.constraints = model, derivation, constraints
        self.nq, self.nv = len(derivation.q), len(derivation.v)
        self.nh, self.nc = constraints.num_holonomic, constraints.jacobian.shape[0]
        self.initial = [c.initial for c in model.coordinates]
        self.param_names = [str(p) for p in derivation.params]
        args = [*derivation.q, *derivation.v, *derivation.params, derivation.t]
        self.holonomic = lambdify_flat(args, constraints.holonomic)
        self.holonomic_jacobian = lambdify_flat(args, constraints.holonomic_jacobian)
        self.jacobian = lambdify_flat(args, constraints.jacobian)
        self.velocity = lambdify_flat(args, constraints.velocity)
        self.bias = lambdify_flat(args, constraints.bias)
        self.mass = lambdify_flat(args, derivation.mass_matrix)
        self.forces = lambdify_flat(args, derivation.applied_forces
                                    + derivation.inertial_forces)

    def defaults(self) -> list[mpmath.mpf]:
        """The parameters at their defaults (an input without one at 0)."""
        default = {p.name: p.default for p in self.model.parameters}
        return [mpmath.mpf(default.get(name, 0.0)) for name in self.param_names]

    def accelerations(self, q, v, params, time):
        """(a, lambda) of Mt a = Ft + Fi + A^T lambda, A a = -gamma (the KKT system)."""
        n, m = self.nv, self.nc
        mass = list(self.mass(*q, *v, *params, time))
        forces = list(self.forces(*q, *v, *params, time))
        jac = list(self.jacobian(*q, *v, *params, time))
        gamma = list(self.bias(*q, *v, *params, time))
        kkt = mpmath.zeros(n + m, n + m)
        rhs = mpmath.zeros(n + m, 1)
        for i in range(n):
            rhs[i] = forces[i]
            for j in range(n):
                kkt[i, j] = mass[i * n + j]
        for k in range(m):
            rhs[n + k] = -gamma[k]
            for j in range(n):
                kkt[n + k, j] = jac[k * n + j]
                kkt[j, n + k] = -jac[k * n + j]
        solution = mpmath.lu_solve(kkt, rhs)
        return [solution[i] for i in range(n)], [solution[n + k] for k in range(m)]


def _central(f, s: mpmath.mpf = STEP) -> list[mpmath.mpf]:
    """d/ds at s = 0 of the list-valued f(s), by a central difference."""
    return [(p - m) / (2 * s) for p, m in zip(f(s), f(-s))]


class FiniteDifferenceTest(unittest.TestCase):
    """The constraint Jacobians, velocities and bias against central differences."""

    def check(self, model: Constrained, spread, seed: int = 0):
        """`spread`: per coordinate, the half-width of its sampling interval about the
        model's initial value."""
        name = model.name
        self.assertEqual(model.nq, model.nv, f"{name}: these models have v = q'")
        self.assertEqual(model.constraints.holonomic_jacobian.shape, (model.nh, model.nq))
        self.assertEqual(model.constraints.jacobian.shape, (model.nc, model.nv))
        self.assertEqual(model.constraints.velocity.shape, (model.nc, 1))
        self.assertEqual(model.constraints.bias.shape, (model.nc, 1))
        rng = random.Random(f"{name}-finite-differences-{seed}")
        worst = mpmath.mpf(0)
        with mpmath.workdps(DIGITS):
            params = model.defaults()
            for state in range(FD_STATES):
                q = [mpmath.mpf(q0 + rng.uniform(-spread[i], spread[i]))
                     for i, q0 in enumerate(model.initial)]
                v = [mpmath.mpf(rng.uniform(-3.0, 3.0)) for _ in range(model.nv)]
                a = [mpmath.mpf(rng.uniform(-10.0, 10.0)) for _ in range(model.nv)]
                time = mpmath.mpf(rng.uniform(0.0, 10.0))
                where = f"{name}, state {state}: q={format_numbers(q, 8)}, v={format_numbers(v, 8)}"

                def at(qs, vs, ts, function):
                    return list(function(*qs, *vs, *params, ts))

                def compare(what, actual, expected):
                    error = relative_error(actual, expected)
                    self.assertLess(error, FD_TOLERANCE,
                                    f"{what} at {where}\n  generated:          "
                                    f"{format_numbers(actual)}\n  finite differences: "
                                    f"{format_numbers(expected)}")
                    return error

                # (a) holonomic_jacobian = dC/dq, column by column
                if model.nh:
                    generated = at(q, v, time, model.holonomic_jacobian)
                    columns = []
                    for j in range(model.nq):
                        columns.append(_central(lambda s: at(
                            [qk + (s if k == j else 0) for k, qk in enumerate(q)], v, time,
                            model.holonomic)))
                    numeric = [columns[j][i] for i in range(model.nh) for j in range(model.nq)]
                    worst = max(worst, compare("holonomic_jacobian != dC/dq", generated,
                                               numeric))
                # (b) A = d(A v + b)/dv
                generated = at(q, v, time, model.jacobian)
                columns = []
                for j in range(model.nv):
                    columns.append(_central(lambda s: at(
                        q, [vk + (s if k == j else 0) for k, vk in enumerate(v)], time,
                        model.velocity)))
                numeric = [columns[j][i] for i in range(model.nc) for j in range(model.nv)]
                worst = max(worst, compare("A != d(A v + b)/dv", generated, numeric))
                # (c) holonomic rows of A v + b = dC/dt along q' = v
                if model.nh:
                    generated = at(q, v, time, model.velocity)[:model.nh]
                    numeric = _central(lambda s: at(
                        [qk + s * vk for qk, vk in zip(q, v)], v, time + s, model.holonomic))
                    worst = max(worst, compare("holonomic rows of A v + b != dC/dt",
                                               generated, numeric))
                # (d) A a + gamma = d/dt (A v + b) along q' = v, v' = a
                jac = at(q, v, time, model.jacobian)
                gamma = at(q, v, time, model.bias)
                generated = [sum(jac[i * model.nv + j] * a[j] for j in range(model.nv))
                             + gamma[i] for i in range(model.nc)]
                numeric = _central(lambda s: at(
                    [qk + s * vk + s * s / 2 * ak for qk, vk, ak in zip(q, v, a)],
                    [vk + s * ak for vk, ak in zip(v, a)], time + s, model.velocity))
                worst = max(worst, compare("A a + gamma != d/dt (A v + b)", generated,
                                           numeric))
        return worst

    def test_four_bar(self):
        self.check(Constrained(MODELS / "four_bar.py"), spread=[0.2, 0.2, 0.2])

    def test_rolling_coin(self):
        self.check(Constrained(CONSTRAINED / "rolling_coin.py"),
                   spread=[1.0, 1.0, math.pi, math.pi])

    def test_cartesian_pendulum(self):
        self.check(Constrained(CONSTRAINED / "cartesian_pendulum.py"), spread=[0.2, 0.2])

    def test_the_check_detects_a_wrong_bias(self):
        """Not vacuous: a gamma with the crank angle's sign flipped is rejected."""
        model = Constrained(MODELS / "four_bar.py")
        derivation = model.derivation
        crank = derivation.q[0]
        model.bias = lambdify_flat(
            [*derivation.q, *derivation.v, *derivation.params, derivation.t],
            model.constraints.bias.xreplace({crank: -crank}))
        with self.assertRaises(AssertionError):
            self.check(model, spread=[0.2, 0.2, 0.2])


class FourBarKane:
    """The four-bar by Kane's method: q1 (crank) independent, q2 (coupler) and q3 (rocker)
    dependent; the full system mass_matrix u' = forcing holds the reduced equation and the
    differentiated velocity constraints, so it gives all three accelerations."""

    def __init__(self):
        q1, q2, q3 = me.dynamicsymbols("q1 q2 q3")
        u1, u2, u3 = me.dynamicsymbols("u1 u2 u3")
        a, b, c, d, m_a, m_b, m_c, g, torque = sp.symbols("a b c d m_a m_b m_c g u")
        N = me.ReferenceFrame("N")
        crank = N.orientnew("crank", "Axis", (q1, N.z))
        coupler = N.orientnew("coupler", "Axis", (q2, N.z))
        rocker = N.orientnew("rocker", "Axis", (q3, N.z))
        for frame, speed in ((crank, u1), (coupler, u2), (rocker, u3)):
            frame.set_ang_vel(N, speed * N.z)
        A = me.Point("A")          # ground pivot of the crank
        A.set_vel(N, 0)
        D = A.locatenew("D", d * N.x)  # ground pivot of the rocker
        D.set_vel(N, 0)
        B = A.locatenew("B", a * crank.x)
        B.v2pt_theory(A, N, crank)
        crank_middle = A.locatenew("crank_middle", a / 2 * crank.x)
        crank_middle.v2pt_theory(A, N, crank)
        coupler_middle = B.locatenew("coupler_middle", b / 2 * coupler.x)
        coupler_middle.v2pt_theory(B, N, coupler)
        rocker_middle = D.locatenew("rocker_middle", c / 2 * rocker.x)
        rocker_middle.v2pt_theory(D, N, rocker)

        def bar(name, frame, middle, mass, length):
            inertia = me.inertia(frame, 0, 0, mass * length**2 / 12)
            return me.RigidBody(name, middle, frame, mass, (inertia, middle))

        bodies = [bar("crank_bar", crank, crank_middle, m_a, a),
                  bar("coupler_bar", coupler, coupler_middle, m_b, b),
                  bar("rocker_bar", rocker, rocker_middle, m_c, c)]
        loads = [(crank_middle, -m_a * g * N.y), (coupler_middle, -m_b * g * N.y),
                 (rocker_middle, -m_c * g * N.y), (crank, torque * N.z)]
        # the coupler's end C (from B) meets the rocker's tip (from D)
        loop = (B.pos_from(A) + b * coupler.x) - (D.pos_from(A) + c * rocker.x)
        closure = [loop.dot(N.x), loop.dot(N.y)]
        loop_rate = loop.dt(N)  # through the frames' angular velocities: in u1, u2, u3
        kane = me.KanesMethod(
            N, q_ind=[q1], u_ind=[u1], kd_eqs=[q1.diff(t) - u1, q2.diff(t) - u2,
                                               q3.diff(t) - u3],
            q_dependent=[q2, q3], configuration_constraints=closure,
            u_dependent=[u2, u3],
            velocity_constraints=[loop_rate.dot(N.x), loop_rate.dot(N.y)])
        kane.kanes_equations(bodies, loads)
        self.coordinates = [q1, q2, q3]
        self.speeds = [u1, u2, u3]
        self.parameters = {"a": a, "b": b, "c": c, "d": d, "m_a": m_a, "m_b": m_b,
                           "m_c": m_c, "g": g, "u": torque}
        self.mass_matrix = kane.mass_matrix   # 3 x 3: reduced equation, then constraints
        self.forcing = kane.forcing

    def functions(self, param_names):
        """(mass matrix, forcing) as functions of (q1, q2, q3, u1, u2, u3, *params)."""
        qs = sp.symbols("arg_q1:4")
        us = sp.symbols("arg_u1:4")
        ps = [sp.Symbol(f"arg_{name}") for name in param_names]
        substitution = {}
        for q, u, plain_q, plain_u in zip(self.coordinates, self.speeds, qs, us):
            substitution[q.diff(t)] = plain_u
            substitution[u] = plain_u
            substitution[q] = plain_q
        for name, plain in zip(param_names, ps):
            substitution[self.parameters[name]] = plain
        mass = me.msubs(self.mass_matrix, substitution)
        forcing = me.msubs(self.forcing, substitution)
        args = [*qs, *us, *ps]
        leftover = (mass.free_symbols | forcing.free_symbols) - set(args) - {t}
        if leftover or me.find_dynamicsymbols(mass) | me.find_dynamicsymbols(forcing):
            raise AssertionError(f"Kane's equations still use {leftover} after substitution")
        return lambdify_flat(args, mass), lambdify_flat(args, forcing)


def _loop_state(lengths, crank, initial):
    """(coupler, rocker) closing the loop at `crank`, followed from the model's initial
    configuration in small steps (the same assembly branch throughout)."""
    a, b, c, d = lengths

    def closure(q1, q2, q3):
        return [a * mpmath.cos(q1) + b * mpmath.cos(q2) - d - c * mpmath.cos(q3),
                a * mpmath.sin(q1) + b * mpmath.sin(q2) - c * mpmath.sin(q3)]

    start = mpmath.mpf(initial[0])
    guess = [mpmath.mpf(initial[1]), mpmath.mpf(initial[2])]
    steps = 16
    for k in range(steps + 1):
        q1 = start + (crank - start) * k / steps
        solution = mpmath.findroot(lambda q2, q3: closure(q1, q2, q3), guess)
        guess = [solution[0], solution[1]]
    residual = max(abs(r) for r in closure(crank, *guess))
    if residual > mpmath.mpf(10) ** (5 - DIGITS):
        raise AssertionError(f"loop closure not solved: residual {residual}")
    return guess


def _dependent_rates(lengths, q, crank_rate):
    """(coupler', rocker') from the time derivative of the closure, written out by hand."""
    a, b, c, _ = lengths
    q1, q2, q3 = q
    # -a s1 w1 - b s2 w2 + c s3 w3 = 0,  a c1 w1 + b c2 w2 - c c3 w3 = 0
    matrix = mpmath.matrix([[-b * mpmath.sin(q2), c * mpmath.sin(q3)],
                            [b * mpmath.cos(q2), -c * mpmath.cos(q3)]])
    rhs = mpmath.matrix([a * mpmath.sin(q1) * crank_rate, -a * mpmath.cos(q1) * crank_rate])
    rates = mpmath.lu_solve(matrix, rhs)
    return [rates[0], rates[1]]


class FourBarKaneTest(unittest.TestCase):
    """The generated four-bar's constrained accelerations against Kane's method."""

    @classmethod
    def setUpClass(cls):
        cls.model = Constrained(MODELS / "four_bar.py")
        cls.reference = FourBarKane()
        # a tuple: functions stored on the class itself would become methods
        cls.reference_functions = cls.reference.functions(cls.model.param_names)

    def kane_accelerations(self, q, v, params):
        """All three accelerations from Kane's mass_matrix u' = forcing."""
        mass_function, forcing_function = self.reference_functions
        flat = list(mass_function(*q, *v, *params))
        mass = mpmath.matrix([flat[3 * i:3 * i + 3] for i in range(3)])
        solution = mpmath.lu_solve(mass, mpmath.matrix(list(forcing_function(*q, *v, *params))))
        return [solution[i] for i in range(3)]

    def test_the_parameters_and_coordinates_match(self):
        self.assertEqual([str(q) for q in self.model.derivation.q],
                         ["crank", "coupler", "rocker"])
        self.assertEqual(sorted(self.model.param_names), sorted(self.reference.parameters))
        self.assertEqual(self.model.nh, 2)
        self.assertEqual(self.model.nc, 2)
        self.assertEqual(self.reference.mass_matrix.shape, (3, 3))
        self.assertEqual(self.reference.forcing.shape, (3, 1))

    def states(self, count: int, seed: str):
        """Seeded random states on the loop: (q, v, params) with the crank angle and rate
        chosen, the other angles and rates from the closure; lengths near the defaults
        (still a Grashof crank-rocker: the crank turns all the way), masses, g and a nonzero
        motor torque random."""
        model = self.model
        rng = random.Random(seed)
        default = dict(zip(model.param_names, model.defaults()))
        for _ in range(count):
            values = {}
            for name in model.param_names:
                if name in ("a", "b", "c", "d"):
                    values[name] = default[name] * mpmath.mpf(rng.uniform(0.95, 1.05))
                elif name == "g":
                    values[name] = mpmath.mpf(rng.uniform(1.0, 25.0))
                elif name == "u":
                    values[name] = mpmath.mpf(rng.choice((-1, 1)) * rng.uniform(0.5, 20.0))
                else:
                    values[name] = mpmath.mpf(rng.uniform(0.2, 3.0))
            lengths = [values[n] for n in ("a", "b", "c", "d")]
            # a Grashof crank turns all the way round
            crank = mpmath.mpf(model.initial[0] + rng.uniform(-math.pi, math.pi))
            crank_rate = mpmath.mpf(rng.uniform(-4.0, 4.0))
            coupler, rocker = _loop_state(lengths, crank, model.initial)
            q = [crank, coupler, rocker]
            v = [crank_rate, *_dependent_rates(lengths, q, crank_rate)]
            yield q, v, [values[n] for n in model.param_names]

    def test_constrained_accelerations_agree_with_kane(self):
        self.compare_with_kane()

    def compare_with_kane(self):
        """Asserts the agreement at KANE_STATES states; returns the worst relative error."""
        model = self.model
        time = mpmath.mpf(0)
        worst = mpmath.mpf(0)
        with mpmath.workdps(DIGITS):
            for state, (q, v, params) in enumerate(
                    self.states(KANE_STATES, "four_bar-kane")):
                # the generated constraints hold at the state (same loop, same rates)
                self.assertLess(max(abs(x) for x in model.holonomic(*q, *v, *params, time)),
                                mpmath.mpf(10) ** (5 - DIGITS))
                self.assertLess(max(abs(x) for x in model.velocity(*q, *v, *params, time)),
                                mpmath.mpf(10) ** (5 - DIGITS))
                generated, multipliers = model.accelerations(q, v, params, time)
                expected = self.kane_accelerations(q, v, params)
                where = (f"state {state}: q={format_numbers(q, 10)}, v={format_numbers(v, 10)}, "
                         f"{', '.join(model.param_names)}={format_numbers(params, 8)}")
                error = relative_error(generated, expected)
                self.assertLess(error, KANE_TOLERANCE,
                                f"four-bar accelerations differ at {where}\n"
                                f"  generated (KKT): {format_numbers(generated)}\n"
                                f"  Kane:            {format_numbers(expected)}\n"
                                f"  multipliers:     {format_numbers(multipliers)}")
                # not vacuous: the loop's forces matter (the unconstrained Mt a = Ft + Fi
                # is far from it)
                n = model.nv
                mass_t = mpmath.matrix([list(model.mass(*q, *v, *params, time))[n * i:n * i + n]
                                        for i in range(n)])
                free = mpmath.lu_solve(mass_t, mpmath.matrix(
                    list(model.forces(*q, *v, *params, time))))
                self.assertGreater(relative_error([free[i] for i in range(n)], expected),
                                   mpmath.mpf("1e-3"))
                worst = max(worst, error)
        return worst

    def test_the_comparison_detects_a_wrong_torque(self):
        """Not vacuous: the torque's sign flipped on the Kane side is rejected."""
        model = self.model
        index = model.param_names.index("u")
        time = mpmath.mpf(0)
        with mpmath.workdps(DIGITS):
            q, v, params = next(self.states(1, "four_bar-kane-wrong"))
            generated, _ = model.accelerations(q, v, params, time)
            flipped = list(params)
            flipped[index] = -flipped[index]
            self.assertGreater(relative_error(generated,
                                              self.kane_accelerations(q, v, flipped)),
                               mpmath.mpf("1e-3"))


if __name__ == "__main__":
    unittest.main()
