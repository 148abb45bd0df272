# SPDX-License-Identifier: BSD-3-Clause
"""Rigid bodies: the generator's Mt, Ft + Fi, kinetic energy and angular momentum agree with an
independent sympy.physics.mechanics derivation built from RigidBody and inertia() dyadics.

A body in gencoord is a set of point masses with its mass, centre of mass and inertia tensor
(gencoord/dsl/bodies.py); the references below never see those point masses: each body is a
mechanics RigidBody with its inertia dyadic about its centre of mass, its frame oriented by
axis rotations, and Kane's method with generalized speeds u = qdot. Both sides are evaluated
in 30-digit arithmetic at seeded random states and random parameter values (valid inertia
tensors: random principal axes, principal moments that satisfy the triangle inequality) and
must agree to 1e-12 relative:
    generated:  Mt(q) qddot = Ft + Fi,  T,  sum m x cross xdot
    mechanics:  mass_matrix udot = forcing,  kinetic_energy,  angular_momentum(origin)
"""

from __future__ import annotations

import math
import random
import unittest
from pathlib import Path

import mpmath
import sympy as sp
from sympy.physics import mechanics as me

from gencoord.derive.dense import derive
from gencoord.generate.load import load_model

from .graph_values import GraphFunction
from .support import DIGITS, MODELS, format_numbers, relative_error

STATES = 24
TOLERANCE = 1e-12
USER_MODELS = Path(__file__).resolve().parent / "user_models"
t = me.dynamicsymbols._t


def compiled(args, matrix):
    """The entries of `matrix` (row major) as mpmath numbers, a function of `args`; shared
    subexpressions are evaluated once (these expressions have tens of thousands of
    operations)."""
    return GraphFunction(args, list(matrix))


class Reference:
    """A mechanics derivation of a model: named outputs (matrices) in dynamic symbols.

    `coordinates` maps each model coordinate name to its q(t), `speeds` to its u(t) (u = qdot),
    `parameters` each parameter name to its symbol; `outputs` holds 'mass', 'forcing' and
    optionally 'kinetic', 'potential', 'angular_momentum'.
    """

    def __init__(self, coordinates, speeds, parameters, outputs):
        self.coordinates = coordinates
        self.speeds = speeds
        self.parameters = parameters
        self.outputs = outputs

    def function(self, output: str, names: list[str]):
        """The output as a function of values ordered like `names` (coordinates, then their
        rates named <q>_dot, then parameters)."""
        plain = {name: sp.Symbol(f"arg_{name}") for name in names}
        substitution = {}
        for name, q in self.coordinates.items():
            substitution[q.diff(t)] = plain[f"{name}_dot"]
            substitution[self.speeds[name]] = plain[f"{name}_dot"]
            substitution[q] = plain[name]
        for name, symbol in self.parameters.items():
            substitution[symbol] = plain[name]
        value = me.msubs(sp.Matrix(self.outputs[output]), substitution)
        args = [plain[name] for name in names]
        leftover = value.free_symbols - set(args) - {t}
        if leftover:
            raise AssertionError(f"reference {output} still uses {leftover}")
        if me.find_dynamicsymbols(value):
            raise AssertionError(f"reference {output} still has dynamic symbols")
        return compiled(args, value)


def _kane(frame, coordinates, speeds, bodies, loads):
    kd = [coordinates[name].diff(t) - speeds[name] for name in coordinates]
    kane = me.KanesMethod(frame, q_ind=list(coordinates.values()),
                          u_ind=[speeds[name] for name in coordinates], kd_eqs=kd)
    kane.kanes_equations(bodies, loads)
    return kane.mass_matrix, kane.forcing


def _vector(frame, components):
    return sum((c * axis for c, axis in zip(components, (frame.x, frame.y, frame.z))),
               me.Vector(0))


def _inertia_symbols(name):
    """Symbols name_xx, name_yy, name_zz, name_xy, name_yz, name_xz: a tensor's entries."""
    return {key: sp.Symbol(f"{name}_{key}") for key in ("xx", "yy", "zz", "xy", "yz", "xz")}


def double_pendulum_reference() -> Reference:
    """Body 1 hinged at the origin about the world axis (4, 0, 3)/5, body 2 hinged at j
    (body 1's axes) about body 1's axis (0, 3, 4)/5; full inertia dyadics; gravity -g z."""
    q1, q2 = me.dynamicsymbols("q1 q2")
    u1, u2 = me.dynamicsymbols("u1 u2")
    g, m1, m2 = sp.symbols("g m1 m2")
    c1 = sp.symbols("c1x c1y c1z")
    j = sp.symbols("jx jy jz")
    c2 = sp.symbols("c2x c2y c2z")
    I1, I2 = _inertia_symbols("I1"), _inertia_symbols("I2")
    N = me.ReferenceFrame("N")
    axis1 = (4 * N.x + 3 * N.z) / 5
    A = N.orientnew("A", "Axis", (q1, axis1))
    A.set_ang_vel(N, u1 * axis1)
    axis2 = (3 * A.y + 4 * A.z) / 5
    B = A.orientnew("B", "Axis", (q2, axis2))
    B.set_ang_vel(A, u2 * axis2)
    O = me.Point("O")
    O.set_vel(N, 0)
    P1 = O.locatenew("P1", _vector(A, c1))
    P1.v2pt_theory(O, N, A)
    H = O.locatenew("H", _vector(A, j))
    H.v2pt_theory(O, N, A)
    P2 = H.locatenew("P2", _vector(B, c2))
    P2.v2pt_theory(H, N, B)
    bodies = [me.RigidBody("body1", P1, A, m1,
                           (me.inertia(A, I1["xx"], I1["yy"], I1["zz"], I1["xy"], I1["yz"],
                                       I1["xz"]), P1)),
              me.RigidBody("body2", P2, B, m2,
                           (me.inertia(B, I2["xx"], I2["yy"], I2["zz"], I2["xy"], I2["yz"],
                                       I2["xz"]), P2))]
    loads = [(P1, -m1 * g * N.z), (P2, -m2 * g * N.z)]
    coordinates = {"q1": q1, "q2": q2}
    speeds = {"q1": u1, "q2": u2}
    mass, forcing = _kane(N, coordinates, speeds, bodies, loads)
    parameters = {"g": g, "m1": m1, "m2": m2}
    for name, symbols in (("c1", c1), ("j", j), ("c2", c2)):
        parameters.update({str(s): s for s in symbols})
    for tensor in (I1, I2):
        parameters.update({str(s): s for s in tensor.values()})
    outputs = {
        "mass": mass, "forcing": forcing,
        "kinetic": [sum(body.kinetic_energy(N) for body in bodies)],
        "angular_momentum": sum((body.angular_momentum(O, N) for body in bodies),
                                me.Vector(0)).to_matrix(N),
    }
    return Reference(coordinates, speeds, parameters, outputs)


def heavy_top_reference() -> Reference:
    """Z-X-Z Euler angles: A turned by phi about N.z, T by theta about A.x, B by psi about
    T.z; the tip at the fixed origin, the centre of mass at d along B.z; the disc a uniform
    cylinder of radius r and thickness h (moments m (3 r^2 + h^2) / 12 twice, m r^2 / 2)."""
    phi, theta, psi = me.dynamicsymbols("phi theta psi")
    w_phi, w_theta, w_psi = me.dynamicsymbols("w_phi w_theta w_psi")
    m, d, r, h, g = sp.symbols("m d r h g")
    transverse, axial = m * (3 * r**2 + h**2) / 12, m * r**2 / 2
    N = me.ReferenceFrame("N")
    A = N.orientnew("A", "Axis", (phi, N.z))
    A.set_ang_vel(N, w_phi * N.z)
    T = A.orientnew("T", "Axis", (theta, A.x))
    T.set_ang_vel(A, w_theta * A.x)
    B = T.orientnew("B", "Axis", (psi, T.z))
    B.set_ang_vel(T, w_psi * T.z)
    O = me.Point("O")
    O.set_vel(N, 0)
    P = O.locatenew("P", d * B.z)
    P.v2pt_theory(O, N, B)
    top = me.RigidBody("top", P, B, m, (me.inertia(B, transverse, transverse, axial), P))
    coordinates = {"phi": phi, "theta": theta, "psi": psi}
    speeds = {"phi": w_phi, "theta": w_theta, "psi": w_psi}
    mass, forcing = _kane(N, coordinates, speeds, [top], [(P, -m * g * N.z)])
    outputs = {
        "mass": mass, "forcing": forcing,
        "kinetic": [top.kinetic_energy(N)],
        "potential": [m * g * P.pos_from(O).dot(N.z)],
        "angular_momentum": top.angular_momentum(O, N).to_matrix(N),
    }
    return Reference(coordinates, speeds, {"m": m, "d": d, "r": r, "h": h, "g": g}, outputs)


def _random_rotation(rng: random.Random) -> list[list[float]]:
    """A random rotation matrix, from a normalized Gaussian quaternion."""
    w, x, y, z = (rng.gauss(0.0, 1.0) for _ in range(4))
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def _principal_moments(rng: random.Random) -> list[float]:
    """Three moments of a possible body: each less than the sum of the other two, by a margin."""
    first, second = rng.uniform(0.2, 3.0), rng.uniform(0.2, 3.0)
    low, high = abs(first - second), first + second
    return [first, second, rng.uniform(low + 0.1 * (high - low), high - 0.1 * (high - low))]


def random_inertia(rng: random.Random) -> dict[str, float]:
    """The entries of Q diag(moments) Q^T for a random rotation Q: a full, valid tensor."""
    Q, moments = _random_rotation(rng), _principal_moments(rng)
    entry = {}
    for key, (i, j) in {"xx": (0, 0), "yy": (1, 1), "zz": (2, 2), "xy": (0, 1), "yz": (1, 2),
                        "xz": (0, 2)}.items():
        entry[key] = sum(Q[i][k] * moments[k] * Q[j][k] for k in range(3))
    return entry


def double_pendulum_parameters(rng: random.Random) -> dict[str, float]:
    values = {"g": rng.uniform(1.0, 25.0), "m1": rng.uniform(0.2, 3.0),
              "m2": rng.uniform(0.2, 3.0)}
    for name in ("c1", "j", "c2"):
        values.update({f"{name}{axis}": rng.uniform(-1.0, 1.0) for axis in "xyz"})
    for name in ("I1", "I2"):
        values.update({f"{name}_{key}": value for key, value in random_inertia(rng).items()})
    return values


def heavy_top_parameters(rng: random.Random) -> dict[str, float]:
    return {"m": rng.uniform(0.2, 3.0), "d": rng.uniform(0.05, 2.0), "r": rng.uniform(0.05, 2.0),
            "h": rng.uniform(0.01, 2.0), "g": rng.uniform(1.0, 25.0)}


class RigidBodyDerivationTest(unittest.TestCase):
    """Generated Mt, Ft + Fi, T and L vs a sympy.physics.mechanics RigidBody derivation."""

    def compare(self, path: Path, reference: Reference, parameters, coordinate_range=None,
                extra=("kinetic", "angular_momentum")):
        """The worst relative error of each compared output over STATES random states.

        `parameters(rng)` draws the parameter values; `coordinate_range` maps a coordinate
        name to its (low, high) sampling interval (default (-pi, pi))."""
        model, name, _ = load_model(str(path))
        derivation = derive(model)
        q_names = [str(q) for q in derivation.q]
        self.assertEqual(sorted(q_names), sorted(reference.coordinates),
                         f"{name}: coordinates of the model and the reference differ")
        param_names = [str(p) for p in derivation.params]
        self.assertEqual(sorted(param_names), sorted(reference.parameters),
                         f"{name}: parameters of the model and the reference differ")
        self.assertEqual([str(v) for v in derivation.v], [f"{q}_dot" for q in q_names])
        names = q_names + [f"{q}_dot" for q in q_names] + param_names
        args = [*derivation.q, *derivation.v, *derivation.params]
        generated = {
            "mass": derivation.mass_matrix,
            "forcing": derivation.applied_forces + derivation.inertial_forces,
            "kinetic": [derivation.kinetic_energy],
            "potential": [derivation.potential_energy],
            "angular_momentum": derivation.angular_momentum,
        }
        outputs = ("mass", "forcing", *extra)
        ours = {key: compiled(args, generated[key]) for key in outputs}
        theirs = {key: reference.function(key, names) for key in outputs}

        rng = random.Random(f"{name}-rigid")
        coordinate_range = coordinate_range or {}
        worst = {key: mpmath.mpf(0) for key in outputs}
        with mpmath.workdps(DIGITS):
            for state in range(STATES):
                values = dict(parameters(rng))
                for q in q_names:
                    values[q] = rng.uniform(*coordinate_range.get(q, (-math.pi, math.pi)))
                    values[f"{q}_dot"] = rng.uniform(-4.0, 4.0)
                point = [mpmath.mpf(values[n]) for n in names]
                where = (f"{name}, state {state}: "
                         + ", ".join(f"{n}={values[n]!r}" for n in names))
                for key in outputs:
                    mine, reference_value = ours[key](*point), theirs[key](*point)
                    error = relative_error(mine, reference_value)
                    self.assertLess(error, TOLERANCE,
                                    f"{key} differs from mechanics' at {where}\n"
                                    f"  generated: {format_numbers(mine)}\n"
                                    f"  mechanics: {format_numbers(reference_value)}")
                    worst[key] = max(worst[key], error)
        return worst

    def test_compound_double_pendulum_with_full_inertia_tensors(self):
        self.compare(USER_MODELS / "compound_double_pendulum_3d.py", double_pendulum_reference(),
                     double_pendulum_parameters)

    def test_heavy_top(self):
        # theta = 0 and pi are the Euler angles' singularities: stay clear of them
        self.compare(MODELS / "heavy_top.py", heavy_top_reference(), heavy_top_parameters,
                     coordinate_range={"theta": (0.2, math.pi - 0.2)},
                     extra=("kinetic", "potential", "angular_momentum"))

    def test_the_comparison_sees_the_products_of_inertia(self):
        """Not vacuous: a reference with one product of inertia of the other sign (the sign
        convention of a product of inertia, a classic slip) is rejected."""
        reference = double_pendulum_reference()
        flipped = reference.parameters["I2_xz"]
        for key in ("mass", "forcing"):
            reference.outputs[key] = reference.outputs[key].subs(flipped, -flipped)
        with self.assertRaises(AssertionError):
            self.compare(USER_MODELS / "compound_double_pendulum_3d.py", reference,
                         double_pendulum_parameters, extra=())

    def test_the_comparison_sees_the_thickness_of_the_top(self):
        """Not vacuous: the top taken as a flat disc (h = 0 in the reference only, so its
        transverse moment is m r^2 / 4) is rejected."""
        reference = heavy_top_reference()
        h = reference.parameters["h"]
        for key in ("mass", "forcing"):
            reference.outputs[key] = reference.outputs[key].subs(h, 0)
        with self.assertRaises(AssertionError):
            self.compare(MODELS / "heavy_top.py", reference, heavy_top_parameters,
                         coordinate_range={"theta": (0.2, math.pi - 0.2)}, extra=())


if __name__ == "__main__":
    unittest.main()
