# SPDX-License-Identifier: BSD-3-Clause
"""A rigid body as point masses with its mass, centre of mass and inertia tensor.

A body is the continuum x = p(q, t) + R(q, t) r over its mass. Everything the dynamics takes
from it (kinetic energy, Mt, Fi, gravity's force and potential, the momenta) is an integral
over the mass of an expression at most quadratic in r, so it depends on the distribution
only through the mass m, the first moment (zero about the centre of mass) and the second
moment S = integral of r r^T dm = tr(I)/2 1 - I. Point masses with these three moments give
each of them exactly; in particular their Mt is m J_p^T J_p + J_w^T I J_w, J_w the
angular-velocity Jacobian.

- 3D: four masses m/4 at r_k = L c_k / sqrt(m), where S = L L^T (Cholesky) and c_k are the
  vertices (+-1, +-1, +-1) of a regular tetrahedron (sum c_k = 0, sum c_k c_k^T = 4 1).
- 2D: three masses m/3 at distance sqrt(I/m) from the centre, 120 degrees apart.

The point masses are particles to the kinematics, the forces and the maximal-coordinate
model (the body adds rods between them, which keep it rigid where they move freely). The
reduced inertia takes the body whole instead (`inertial_terms`): the same values in fewer,
shorter expressions, in which what vanishes identically cancels structurally.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import sympy as sp

from gencoord.errors import ModelError
from gencoord.dsl.items import Body, BodyParticle, BodyPoint, Point, point_symbols

if TYPE_CHECKING:  # annotations only: model.py imports this module
    from gencoord.dsl.model import Model

_TETRAHEDRON = [(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)]
_TRIANGLE = [(0, 1), (-sp.sqrt(3) / 2, -sp.Rational(1, 2)), (sp.sqrt(3) / 2, -sp.Rational(1, 2))]


def as_inertia(inertia, dim: int, label: str, line: int | None) -> sp.Matrix:
    """The inertia tensor as a symmetric dim-3 3x3 matrix (1x1 in 2D), or a ModelError."""
    try:
        matrix = sp.Matrix(inertia) if dim == 3 else sp.Matrix([sp.sympify(inertia)])
    except (TypeError, ValueError, sp.SympifyError) as error:
        raise ModelError(f"inertia is not {'a 3x3 matrix' if dim == 3 else 'a scalar'} "
                         f"({error})", item=label, line=line) from None
    if dim == 3 and matrix.shape != (3, 3):
        raise ModelError(f"inertia is {matrix.shape[0]}x{matrix.shape[1]}; give the 3x3 tensor "
                         "about the centre of mass in body axes", item=label, line=line)
    if dim == 3 and not all(_equal_to_round_off(matrix[i, j], matrix[j, i])
                            for i in range(3) for j in range(i)):
        raise ModelError("inertia is not symmetric; give the tensor about the centre of mass "
                         "with I[i, j] = I[j, i]", item=label, line=line)
    return (matrix + matrix.T) / 2 if dim == 3 else matrix


def _equal_to_round_off(a: sp.Expr, b: sp.Expr) -> bool:
    """a == b, up to the round-off of floating-point coefficients (a tensor turned by a
    numeric rotation, R I R^T, is symmetric only to round-off)."""
    difference = sp.expand(a - b)
    if difference == 0:
        return True
    size = max([abs(c) for c in sp.expand(a).as_coefficients_dict().values()]
               + [abs(c) for c in sp.expand(b).as_coefficients_dict().values()])
    return all(c.is_Float and abs(c) <= 1e-12 * size
               for c in difference.as_coefficients_dict().values())


def inertia_problem(mass, inertia: sp.Matrix) -> str | None:
    """Why a (numeric) mass and inertia tensor cannot be a rigid body's, or None."""
    if not (mass.is_number and mass.is_extended_positive and mass.is_finite):
        return f"mass is {mass}; a body's mass must be positive"
    if inertia.shape == (1, 1):
        if not (inertia[0].is_extended_positive and inertia[0].is_finite):
            return f"inertia is {inertia[0]}; a 2D body's moment of inertia must be positive"
        return None
    moments = [float(value) for value in sp.Matrix(inertia).evalf().eigenvals(multiple=True)]
    scale = max(abs(value) for value in moments) or 1.0
    if min(moments) <= 1e-12 * scale:
        return (f"inertia has principal moments {_listed(moments)}, not all positive: it is not "
                "positive definite; give the tensor about the centre of mass of a real body")
    for moment in moments:
        others = sum(moments) - moment
        if moment >= others * (1 - 1e-12):
            return (f"inertia has principal moments {_listed(moments)}: {moment:.6g} is not "
                    "less than the sum of the other two (the triangle inequality), which no "
                    "mass distribution allows (a flat body or a thin rod needs some thickness)")
    return None


def _listed(values: list[float]) -> str:
    return ", ".join(f"{value:.6g}" for value in sorted(values))


def second_moment(inertia: sp.Matrix) -> sp.Matrix:
    """S = integral of r r^T dm, from the inertia tensor (in 2D, of the planar distribution
    taken isotropic: only tr S = I enters planar motion)."""
    if inertia.shape == (1, 1):
        return sp.eye(2) * inertia[0] / 2
    return sp.eye(3) * inertia.trace() / 2 - inertia


def _offsets(body: Body) -> list[sp.Matrix]:
    """The point masses' offsets from the centre of mass, in body axes."""
    m = body.mass
    if body.frame.dim == 2:
        radius = sp.sqrt(body.inertia[0] / m)
        return [sp.Matrix(corner) * radius for corner in _TRIANGLE]
    assert body.second_moment is not None  # set by add_point_masses before the offsets
    factor = body.second_moment.cholesky(hermitian=False)
    return [factor * sp.Matrix(corner) / sp.sqrt(m) for corner in _TETRAHEDRON]


def add_point_masses(model: Model, body: Body) -> None:
    """Adds the body's point masses as particles, and rods between every two of them."""
    if body.mass.is_number and all(value.is_number for value in body.inertia):
        problem = inertia_problem(body.mass, body.inertia)
        if problem:
            raise ModelError(problem, item=body.label(), line=body.line)
    body.second_moment = second_moment(body.inertia)
    body.offsets = offsets = _offsets(body)
    count = len(offsets)
    for k, r in enumerate(offsets):
        name = f"{body.name}_{k}"
        x, xdot = point_symbols(name, model.dim)
        body.particles.append(BodyParticle(name, body.frame.point(r), x, xdot, body.mass / count,
                                           body_name=body.name, line=body.line))
    model.particles.extend(body.particles)
    for i in range(count):
        for j in range(i + 1, count):
            d = offsets[i] - offsets[j]
            model.rod(body.particles[i], body.particles[j], sp.sqrt(d.dot(d)))


def force_shares(point: Point, force: sp.Matrix) -> list[tuple[Point, sp.Matrix]]:
    """Where a force on `point` acts among the points that carry mass: a body point passes
    w_k f to each of its body's point masses (the same virtual work, since x = sum w_k x_k);
    any other point keeps it."""
    if isinstance(point, BodyPoint):
        return [(particle, weight * force)
                for particle, weight in zip(point.body.particles, point.weights)]
    return [(point, force)]


def torque_generalized_forces(model: Model, q: list[sp.Symbol]) -> sp.Matrix:
    """J_w^T tau for every body torque: the virtual work of tau through the body's virtual
    rotation, whose axis is unskew(dR/dq_a R^T) (2D: the angle's derivative)."""
    forces = sp.zeros(len(q), 1)
    for item in model.torques:
        frame = item.body.frame
        for a, coordinate in enumerate(q):
            if frame.dim == 2:
                if frame.angle is not None:
                    rate = frame.angle.diff(coordinate)
                else:
                    rate = (frame.rotation.diff(coordinate) * frame.rotation.T)[1, 0]
                forces[a] += item.torque[0] * rate
                continue
            spin = frame.rotation.diff(coordinate) * frame.rotation.T
            axis = sp.Matrix([spin[2, 1], spin[0, 2], spin[1, 0]])
            forces[a] += item.torque.dot(axis)
    return forces


@dataclass(frozen=True)
class InertialTerm:
    """A point y(q, t) of weight w whose motion carries the kinetic energy w |ydot|^2 / 2.

    The model's kinetic energy is the sum over its terms, so Mt, Fi and the momenta are sums
    over them as over particles. Translational terms (particles, bodies' centres of mass) carry
    gravity and linear momentum; every term's w y x ydot adds to the angular momentum.
    """
    name: str            # a particle's name, or '<body>.<part>' (no point's name has a dot)
    weight: sp.Expr
    position: sp.Matrix
    translational: bool


def rotational_terms(body: Body) -> list[InertialTerm]:
    """The rotation's energy as terms: integral of |Rdot r|^2 dm / 2 = tr(Rdot S Rdot^T) / 2,
    and with S = sum_k d_k l_k l_k^T (LDL^T, no square roots) that is sum_k d_k |Rdot l_k|^2 / 2:
    terms R l_k of weight d_k. A diagonal S gives the columns of R. In 2D only tr S = I
    enters: one term, the first column of R, of weight I."""
    rotation = body.frame.rotation
    if body.frame.dim == 2:
        return [InertialTerm(f"{body.name}.rotation", body.inertia[0], rotation[:, 0], False)]
    assert body.second_moment is not None  # set with the point masses (add_point_masses)
    unit_lower, diagonal = body.second_moment.LDLdecomposition(hermitian=False)
    return [InertialTerm(f"{body.name}.rotation{k}", diagonal[k, k],
                         rotation * unit_lower[:, k], False) for k in range(3)]


def inertial_terms(model: Model) -> list[InertialTerm]:
    """Every term of the model's kinetic energy: its particles (a body's point masses
    excepted), and each body's centre of mass and rotation."""
    terms = [InertialTerm(p.name, p.mass, p.position, True)
             for p in model.particles if not isinstance(p, BodyParticle)]
    for body in model.bodies:
        terms.append(InertialTerm(f"{body.name}.centre", body.mass, body.frame.origin, True))
        terms.extend(rotational_terms(body))
    return terms
