# SPDX-License-Identifier: BSD-3-Clause
"""The generator's Mt and Ft + Fi agree with an independent sympy.physics.mechanics derivation.

Every reference below is written from scratch with reference frames, points and
Kane's method or Lagrange's method (nothing of gencoord/derive/dense.py is reused); both sides are
evaluated in 30-digit arithmetic at seeded random states (q, v and parameter values) and must
agree to 1e-12 relative. Both are in the model file's coordinates, with v = qdot:
    generated:  Mt(q) qddot = Ft + Fi
    mechanics:  mass_matrix qddot = forcing   (Kane with u = qdot, or Lagrange)
"""

from __future__ import annotations

import math
import random
import unittest

import mpmath
import sympy as sp
from sympy.physics import mechanics as me

from gencoord.derive.dense import derive
from gencoord.generate.load import load_model

from .support import DIGITS, MODELS, format_numbers, lambdify_flat, relative_error

STATES = 24
TOLERANCE = 1e-12
t = me.dynamicsymbols._t


class Reference:
    """A mechanics derivation: M qddot = forcing, in dynamic symbols.

    `coordinates` maps each model coordinate name to its dynamic symbol q(t), `speeds` each
    name to the generalized speed (Kane's u(t), or q'(t) for Lagrange) that equals qdot;
    `parameters` maps parameter names to plain symbols.
    """

    def __init__(self, coordinates, speeds, parameters, mass_matrix, forcing):
        self.coordinates = coordinates
        self.speeds = speeds
        self.parameters = parameters
        self.mass_matrix = mass_matrix
        self.forcing = forcing

    def functions(self, names: list[str]):
        """(mass matrix, forcing) as functions of values ordered like `names`; names ending
        in _dot are the speeds of the coordinate before the suffix, 't' is time."""
        plain = {name: sp.Symbol(f"arg_{name}") for name in names}
        substitution = {}
        for name, q in self.coordinates.items():
            speed = self.speeds[name]
            substitution[q.diff(t)] = plain[f"{name}_dot"]
            substitution[speed] = plain[f"{name}_dot"]
            substitution[q] = plain[name]
        for name, symbol in self.parameters.items():
            substitution[symbol] = plain[name]
        mass = me.msubs(self.mass_matrix, substitution)
        forcing = me.msubs(self.forcing, substitution)
        args = [plain[name] for name in names]
        leftover = (mass.free_symbols | forcing.free_symbols) - set(args) - {t}
        if leftover:
            raise AssertionError(f"reference still uses {leftover} after substitution")
        if me.find_dynamicsymbols(mass) | me.find_dynamicsymbols(forcing):
            raise AssertionError("reference still has dynamic symbols after substitution")
        args.append(t)  # harmless when absent; these models do not depend on time
        return lambdify_flat(args, mass), lambdify_flat(args, forcing)


def _kane(frame, coordinates, speeds, bodies, loads):
    kd = [coordinates[name].diff(t) - speeds[name] for name in coordinates]
    kane = me.KanesMethod(frame, q_ind=list(coordinates.values()),
                          u_ind=[speeds[name] for name in coordinates], kd_eqs=kd)
    kane.kanes_equations(bodies, loads)
    return kane.mass_matrix, kane.forcing


def _lagrange(lagrangian, coordinates, frame=None, loads=None):
    method = me.LagrangesMethod(lagrangian, list(coordinates.values()), forcelist=loads,
                                frame=frame)
    method.form_lagranges_equations()
    return method.mass_matrix, method.forcing


def pendulum_reference() -> Reference:
    """Lagrange, gravity as a potential; the bob hangs at -l along a frame turned by theta."""
    theta = me.dynamicsymbols("theta")
    l, m, g = sp.symbols("l m g")
    N = me.ReferenceFrame("N")
    A = N.orientnew("A", "Axis", (theta, N.z))
    O = me.Point("O")
    O.set_vel(N, 0)
    P = O.locatenew("P", -l * A.y)
    P.v2pt_theory(O, N, A)
    bob = me.Particle("bob", P, m)
    lagrangian = bob.kinetic_energy(N) - m * g * P.pos_from(O).dot(N.y)
    coordinates = {"theta": theta}
    mass, forcing = _lagrange(lagrangian, coordinates)
    return Reference(coordinates, {"theta": theta.diff(t)}, {"l": l, "m": m, "g": g},
                     mass, forcing)


def double_pendulum_reference() -> Reference:
    """Lagrange with gravity as applied loads; absolute angles, frames turned about z."""
    theta1, theta2 = me.dynamicsymbols("theta1 theta2")
    l1, l2, m1, m2, g = sp.symbols("l1 l2 m1 m2 g")
    N = me.ReferenceFrame("N")
    A = N.orientnew("A", "Axis", (theta1, N.z))
    B = N.orientnew("B", "Axis", (theta2, N.z))
    O = me.Point("O")
    O.set_vel(N, 0)
    P1 = O.locatenew("P1", -l1 * A.y)
    P1.v2pt_theory(O, N, A)
    P2 = P1.locatenew("P2", -l2 * B.y)
    P2.v2pt_theory(P1, N, B)
    bodies = [me.Particle("bob1", P1, m1), me.Particle("bob2", P2, m2)]
    lagrangian = sum(body.kinetic_energy(N) for body in bodies)
    coordinates = {"theta1": theta1, "theta2": theta2}
    loads = [(P1, -m1 * g * N.y), (P2, -m2 * g * N.y)]
    mass, forcing = _lagrange(lagrangian, coordinates, frame=N, loads=loads)
    return Reference(coordinates, {k: q.diff(t) for k, q in coordinates.items()},
                     {"l1": l1, "l2": l2, "m1": m1, "m2": m2, "g": g}, mass, forcing)


def chain_reference(n: int) -> Reference:
    """Kane's method for the planar n-link chain with absolute angles."""
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    g = sp.Symbol("g")
    coordinates, speeds, parameters = {}, {}, {"g": g}
    bodies, loads = [], []
    previous = O
    for k in range(1, n + 1):
        q = me.dynamicsymbols(f"theta{k}")
        u = me.dynamicsymbols(f"w{k}")
        l, m = sp.symbols(f"l{k} m{k}")
        coordinates[f"theta{k}"], speeds[f"theta{k}"] = q, u
        parameters[f"l{k}"], parameters[f"m{k}"] = l, m
        frame = N.orientnew(f"A{k}", "Axis", (q, N.z))
        frame.set_ang_vel(N, u * N.z)
        point = previous.locatenew(f"P{k}", -l * frame.y)
        point.v2pt_theory(previous, N, frame)
        bodies.append(me.Particle(f"bob{k}", point, m))
        loads.append((point, -m * g * N.y))
        previous = point
    mass, forcing = _kane(N, coordinates, speeds, bodies, loads)
    return Reference(coordinates, speeds, parameters, mass, forcing)


def cart_pole_reference() -> Reference:
    """Kane's method; the pole frame is turned by -theta so that theta is measured from the
    upward vertical towards +x, as in models/cart_pole.py; u pushes the cart along +x."""
    s, theta = me.dynamicsymbols("s theta")
    w_s, w_theta = me.dynamicsymbols("w_s w_theta")
    l, m_cart, m_pole, g, u = sp.symbols("l m_cart m_pole g u")
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    C = O.locatenew("C", s * N.x)
    C.set_vel(N, w_s * N.x)
    A = N.orientnew("A", "Axis", (-theta, N.z))
    A.set_ang_vel(N, -w_theta * N.z)
    P = C.locatenew("P", l * A.y)
    P.v2pt_theory(C, N, A)
    bodies = [me.Particle("cart", C, m_cart), me.Particle("tip", P, m_pole)]
    loads = [(C, -m_cart * g * N.y + u * N.x), (P, -m_pole * g * N.y)]
    coordinates = {"s": s, "theta": theta}
    speeds = {"s": w_s, "theta": w_theta}
    mass, forcing = _kane(N, coordinates, speeds, bodies, loads)
    return Reference(coordinates, speeds, {"l": l, "m_cart": m_cart, "m_pole": m_pole,
                                           "g": g, "u": u}, mass, forcing)


def spherical_pendulum_reference() -> Reference:
    """Kane's method; the bob's position is written in a frame turned by phi about the
    vertical, so its velocity comes from that frame's angular velocity."""
    theta, phi = me.dynamicsymbols("theta phi")
    w_theta, w_phi = me.dynamicsymbols("w_theta w_phi")
    l, m, g = sp.symbols("l m g")
    N = me.ReferenceFrame("N")
    A = N.orientnew("A", "Axis", (phi, N.z))
    A.set_ang_vel(N, w_phi * N.z)
    O = me.Point("O")
    O.set_vel(N, 0)
    P = O.locatenew("P", l * sp.sin(theta) * A.x - l * sp.cos(theta) * A.z)
    P.set_vel(N, P.pos_from(O).dt(N).subs(theta.diff(t), w_theta))
    coordinates = {"theta": theta, "phi": phi}
    speeds = {"theta": w_theta, "phi": w_phi}
    mass, forcing = _kane(N, coordinates, speeds, [me.Particle("bob", P, m)],
                          [(P, -m * g * N.z)])
    return Reference(coordinates, speeds, {"l": l, "m": m, "g": g}, mass, forcing)


def _parameter_value(name: str, rng: random.Random) -> float:
    """A random but physical value: positive lengths, masses and gravity; any force u."""
    if name == "u":
        return rng.choice((-1, 1)) * rng.uniform(0.5, 20.0)  # nonzero cart force
    if name == "g":
        return rng.uniform(1.0, 25.0)
    return rng.uniform(0.2, 3.0)


class IndependentDerivationTest(unittest.TestCase):
    """Generated Mt and Ft + Fi vs sympy.physics.mechanics at random states."""

    def compare(self, model_file: str, reference: Reference, options=None, seed: int = 0,
                coordinate_range=None):
        """`coordinate_range` maps a coordinate name to its (low, high) sampling interval
        (default (-pi, pi))."""
        model, name, _ = load_model(str(MODELS / model_file), options)
        derivation = derive(model)
        q_names = [str(q) for q in derivation.q]
        self.assertEqual(sorted(q_names), sorted(reference.coordinates),
                         f"{name}: coordinates of the model and the reference differ")
        param_names = [str(p) for p in derivation.params]
        self.assertEqual(sorted(param_names), sorted(reference.parameters),
                         f"{name}: parameters of the model and the reference differ")
        self.assertEqual([str(v) for v in derivation.v], [f"{q}_dot" for q in q_names])
        names = q_names + [f"{q}_dot" for q in q_names] + param_names
        args = [*derivation.q, *derivation.v, *derivation.params, derivation.t]
        generated_mass = lambdify_flat(args, derivation.mass_matrix)
        generated_forces = lambdify_flat(
            args, derivation.applied_forces + derivation.inertial_forces)
        reference_mass, reference_forcing = reference.functions(names)

        rng = random.Random(f"{name}-{seed}")
        coordinate_range = coordinate_range or {}
        worst_mass = worst_forces = mpmath.mpf(0)
        with mpmath.workdps(DIGITS):
            for state in range(STATES):
                values = {}
                for q in q_names:
                    values[q] = rng.uniform(*coordinate_range.get(q, (-math.pi, math.pi)))
                    values[f"{q}_dot"] = rng.uniform(-4.0, 4.0)
                for p in param_names:
                    values[p] = _parameter_value(p, rng)
                point = [mpmath.mpf(values[n]) for n in names]
                time = mpmath.mpf(rng.uniform(0, 10))
                mass = generated_mass(*point, time)
                mass_ref = reference_mass(*point, time)
                forces = generated_forces(*point, time)
                forces_ref = reference_forcing(*point, time)
                where = (f"{name}, state {state}: "
                         + ", ".join(f"{n}={values[n]!r}" for n in names))
                mass_error = relative_error(mass, mass_ref)
                force_error = relative_error(forces, forces_ref)
                self.assertLess(mass_error, TOLERANCE,
                                f"Mt differs from mechanics' mass matrix at {where}\n"
                                f"  generated Mt (row major): {format_numbers(mass)}\n"
                                f"  mechanics M  (row major): {format_numbers(mass_ref)}")
                self.assertLess(force_error, TOLERANCE,
                                f"Ft + Fi differs from mechanics' forcing at {where}\n"
                                f"  generated Ft + Fi: {format_numbers(forces)}\n"
                                f"  mechanics forcing: {format_numbers(forces_ref)}")
                worst_mass = max(worst_mass, mass_error)
                worst_forces = max(worst_forces, force_error)
        return worst_mass, worst_forces

    def test_pendulum(self):
        self.compare("pendulum.py", pendulum_reference())

    def test_double_pendulum(self):
        self.compare("double_pendulum.py", double_pendulum_reference())

    def test_three_link_chain(self):
        self.compare("n_link_chain.py", chain_reference(3), options={"n": "3"})

    def test_cart_pole_with_cart_force(self):
        self.compare("cart_pole.py", cart_pole_reference(),
                     coordinate_range={"s": (-5.0, 5.0)})

    def test_spherical_pendulum_away_from_the_poles(self):
        # theta = 0 and pi are the coordinate singularities (J loses rank): stay clear of them
        self.compare("spherical_pendulum.py", spherical_pendulum_reference(),
                     coordinate_range={"theta": (0.2, math.pi - 0.2)})

    def compare_inverse_dynamics(self, model_file: str, reference: Reference,
                                 coordinate_range=None):
        """The generated residual r = Mt a - Ft - Fi (inverse dynamics, the force that
        produces a) against mechanics' M a - forcing at random states and accelerations."""
        model, name, _ = load_model(str(MODELS / model_file))
        derivation = derive(model)
        q_names = [str(q) for q in derivation.q]
        param_names = [str(p) for p in derivation.params]
        names = q_names + [f"{q}_dot" for q in q_names] + param_names
        args = [*derivation.q, *derivation.v, *derivation.params, *derivation.a, derivation.t]
        residual = lambdify_flat(args, derivation.residual())
        reference_mass, reference_forcing = reference.functions(names)
        rng = random.Random(f"{name}-inverse-dynamics")
        coordinate_range = coordinate_range or {}
        with mpmath.workdps(DIGITS):
            for state in range(STATES):
                values = {}
                for q in q_names:
                    values[q] = rng.uniform(*coordinate_range.get(q, (-math.pi, math.pi)))
                    values[f"{q}_dot"] = rng.uniform(-4.0, 4.0)
                for p in param_names:
                    values[p] = _parameter_value(p, rng)
                point = [mpmath.mpf(values[n]) for n in names]
                accelerations = [mpmath.mpf(rng.uniform(-10.0, 10.0)) for _ in q_names]
                time = mpmath.mpf(rng.uniform(0, 10))
                generated = residual(*point, *accelerations, time)
                n = len(q_names)
                flat = list(reference_mass(*point, time))  # row major
                mass = mpmath.matrix([flat[i * n:(i + 1) * n] for i in range(n)])
                forcing = mpmath.matrix(list(reference_forcing(*point, time)))
                expected = mass * mpmath.matrix(accelerations) - forcing
                error = relative_error(generated, list(expected))
                self.assertLess(error, TOLERANCE,
                                f"{name}, state {state}: inverse dynamics differ\n"
                                f"  generated r:     {format_numbers(generated)}\n"
                                f"  mechanics M a - F: {format_numbers(list(expected))}")

    def test_inverse_dynamics_of_the_double_pendulum(self):
        self.compare_inverse_dynamics("double_pendulum.py", double_pendulum_reference())

    def test_inverse_dynamics_of_the_cart_pole(self):
        self.compare_inverse_dynamics("cart_pole.py", cart_pole_reference(),
                                      coordinate_range={"s": (-5.0, 5.0)})

    def test_the_comparison_detects_a_wrong_reference(self):
        """The check is not vacuous: a reference with a wrong gravity sign is rejected."""
        reference = pendulum_reference()
        g = reference.parameters["g"]
        reference.forcing = reference.forcing.subs(g, -g)
        with self.assertRaises(AssertionError):
            self.compare("pendulum.py", reference)


if __name__ == "__main__":
    unittest.main()
