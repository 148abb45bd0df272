# SPDX-License-Identifier: BSD-3-Clause
"""Reference linearized dynamics of two planar cart systems, derived with Kane's method.

An independent check of gencoord's linearizations, written from scratch with
sympy.physics.mechanics (frames, points, particles, KanesMethod) and nothing of the generator.
Pure SymPy (numbers in mpmath, SymPy's own dependency); works with SymPy 1.11 to 1.14.

Both systems are planar with y up and gravity (0, -g); angles are absolute, from the upward
vertical. The state is x = (q, v) with generalized speeds u = v = qdot, and the input F is a
horizontal force on the cart (a generalized force on s).
    cart_pole:                q = (s, theta);          parameters l, m_cart, m_pole, g
    double_pendulum_on_cart:  q = (s, theta1, theta2); parameters l1, l2, m_cart, m1, m2, g
The cart is a particle m_cart at (s, 0); each link adds a particle at the end of a massless rod
from the previous particle.
"""

from __future__ import annotations

import functools

import mpmath
import sympy as sp
from sympy.physics import mechanics as me

DIGITS = 30

# Per system: coordinate names, then (rod length, bob mass) parameter names of each link.
SYSTEMS = {
    "cart_pole": (("s", "theta"), (("l", "m_pole"),)),
    "double_pendulum_on_cart": (("s", "theta1", "theta2"), (("l1", "m1"), ("l2", "m2"))),
}


def parameter_names(system: str) -> tuple[str, ...]:
    """The names `params` must hold, in a fixed order."""
    links = SYSTEMS[system][1]
    return tuple(name for link in links for name in link) + ("m_cart", "g")


class _Derivation:
    """One system's equations, numerically callable in plain arguments.

    mass_matrix(q, u, F, p) and forcing(q, u, F, p): Kane's M(q) udot = forcing(q, u, F);
    A(q, u, a, F, p) and B(...): KanesMethod.linearize's A and B, where a = udot at the point.
    """

    def __init__(self, system: str):
        coordinate_names, links = SYSTEMS[system]
        n = len(coordinate_names)
        q = me.dynamicsymbols(" ".join(coordinate_names))
        u = me.dynamicsymbols(f"u0:{n}")
        force = me.dynamicsymbols("F")
        p = sp.symbols(parameter_names(system))
        symbol = dict(zip(parameter_names(system), p))
        m_cart, g = symbol["m_cart"], symbol["g"]

        frame = me.ReferenceFrame("N")
        origin = me.Point("O")
        origin.set_vel(frame, 0)
        point = origin.locatenew("cart", q[0] * frame.x)
        particles = [me.Particle("cart_mass", point, m_cart)]
        for k, (length, mass) in enumerate(links, start=1):
            rod = symbol[length] * (sp.sin(q[k]) * frame.x + sp.cos(q[k]) * frame.y)
            point = point.locatenew(f"bob{k}", rod)
            particles.append(me.Particle(f"bob{k}_mass", point, symbol[mass]))
        for particle in particles:
            # In q'; KanesMethod rewrites q' as u through the kinematic equations.
            particle.point.set_vel(frame, particle.point.pos_from(origin).dt(frame))

        loads = [(particles[0].point, force * frame.x)]
        loads += [(b.point, -b.mass * g * frame.y) for b in particles]
        kane = me.KanesMethod(frame, q_ind=q, u_ind=u,
                              kd_eqs=[qk.diff() - uk for qk, uk in zip(q, u)])
        kane.kanes_equations(particles, loads)
        # No new_method (1.11 and 1.14 both ignore it) and no linear_solver (1.14 only): the
        # default symbolic LU solve is what both versions do.
        A, B, inputs = kane.linearize(A_and_B=True)
        assert list(inputs) == [force], inputs

        # Plain symbols for evaluation. A keeps udot: the linearizer differentiates
        # M(q) udot - forcing with respect to q, so d(M udot)/dq stays in terms of udot, which
        # must be the nonlinear acceleration at the operating point (zero only at equilibria).
        qs, us, accelerations = (sp.symbols(f"{c}0:{n}") for c in ("q", "u", "a"))
        f = sp.Symbol("F")
        plain = dict(zip([uk.diff() for uk in u], accelerations))
        plain.update(zip([qk.diff() for qk in q], us))
        plain.update(zip(q, qs))
        plain.update(zip(u, us))
        plain[force] = f

        def callable_of(expression, *arguments):
            expression = me.msubs(expression, plain)
            assert not expression.atoms(sp.Derivative, sp.core.function.AppliedUndef)
            return sp.lambdify(arguments, expression, modules="mpmath", cse=True)

        self.n = n
        self.mass_matrix = callable_of(kane.mass_matrix, qs, us, f, p)
        self.forcing = callable_of(kane.forcing, qs, us, f, p)
        self.A = callable_of(A, qs, us, accelerations, f, p)
        self.B = callable_of(B, qs, us, accelerations, f, p)


@functools.lru_cache(maxsize=None)
def _derivation(system: str) -> _Derivation:
    if system not in SYSTEMS:
        raise ValueError(f"unknown system {system!r}; one of {sorted(SYSTEMS)}")
    return _Derivation(system)


def _arguments(system, q, v, F, params):
    """The derivation and mpmath numbers (q, u, F, p) at the working precision (call within
    mpmath.workdps); checks lengths and parameter names."""
    derivation = _derivation(system)
    names = parameter_names(system)
    if len(q) != derivation.n or len(v) != derivation.n:
        raise ValueError(f"{system}: q and v need {derivation.n} entries each")
    if set(params) != set(names):
        raise ValueError(f"{system}: params must name exactly {names}")
    number = mpmath.mpf
    return (derivation, [number(x) for x in q], [number(x) for x in v], number(F),
            [number(params[name]) for name in names])


def _accelerations(derivation, q, u, F, p):
    """udot = M^-1 forcing, solved numerically (a symbolic inverse would only grow the terms)."""
    mass = mpmath.matrix(derivation.mass_matrix(q, u, F, p))
    forcing = mpmath.matrix(derivation.forcing(q, u, F, p))
    return list(mpmath.lu_solve(mass, forcing))


def _floats(matrix) -> list[list[float]]:
    return [[float(x) for x in row] for row in matrix.tolist()]


def nonlinear_rhs(system: str, q, v, F, params: dict) -> list[float]:
    """(qdot, qddot) = f(x, F) of the Kane derivation, evaluated with 30-digit floats."""
    with mpmath.workdps(DIGITS):
        derivation, q, u, F, p = _arguments(system, q, v, F, params)
        return [float(x) for x in u + _accelerations(derivation, q, u, F, p)]


def linearization(system: str, q, v, F, params: dict
                  ) -> tuple[list[list[float]], list[list[float]]]:
    """A = d(qdot, qddot)/d(q, v) (2n x 2n) and B = d(qdot, qddot)/dF (2n x 1) at the operating
    point, from KanesMethod.linearize, evaluated with 30-digit floats and returned as Python floats.

    Any (q, v, F) works, not only equilibria: the accelerations there are substituted for udot.
    """
    with mpmath.workdps(DIGITS):
        derivation, q, u, F, p = _arguments(system, q, v, F, params)
        a = _accelerations(derivation, q, u, F, p)
        A = mpmath.matrix(derivation.A(q, u, a, F, p))
        B = mpmath.matrix(derivation.B(q, u, a, F, p))
        return _floats(A), _floats(B)
