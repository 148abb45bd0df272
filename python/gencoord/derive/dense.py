# SPDX-License-Identifier: BSD-3-Clause
"""Derives the reduced equations of motion of a model: Mt qddot = Ft + Fi, the contract.

    J = dX/dq,  X_t = dX/dt,  xdot = J v + X_t,  gamma = d(xdot)/dq v + d(xdot)/dt
    Mt = J^T M J,  Ft = J^T F + Q (generalized forces),  Fi = -J^T M gamma
    Mt qddot = Ft + Fi

Everything is accumulated term by term (M is diagonal), so no dense dN x dN matrix is ever
formed, and no expression is simplified: one CSE pass over all outputs comes later. The
inertia's terms are the particles and, for rigid bodies, their centres of mass and rotations
(bodies.inertial_terms); gravity acts at every translational term. The particle-indexed
outputs (positions, J, gamma) keep a body's point masses, whose moments are the body's.
Each output is one flat expression: the pipeline uses this for small models and the tests
use it as the reference; structured.py derives large models as named intermediates.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING, Callable, Literal, Protocol

import sympy as sp

from gencoord.dsl.bodies import InertialTerm, force_shares, inertial_terms
from gencoord.derive.body_jacobian import numeric_body_jacobian
from gencoord.derive.body_tree import body_tree
from gencoord.derive.differentiate import termwise_jacobian
from gencoord.derive.speed_forces import generalized_force_vector, rate_matrix
from gencoord.dsl.model import Model
from gencoord.dsl.items import Point
from gencoord.derive.point_tree import PointTree, point_tree
from gencoord.symbolic.sums import dot, product

if TYPE_CHECKING:
    from gencoord.derive.kinematic_constraints import ConstraintDerivation


@dataclass
class Derivation:
    """All symbolic outputs of one model, as SymPy expressions of q, v, t and parameters;
    v are the speeds (nv of them, q' where the model has no free or ball joint)."""
    q: list[sp.Symbol]
    v: list[sp.Symbol]
    a: list[sp.Symbol]               # accelerations v', input of the inverse dynamics
    t: sp.Symbol
    params: list[sp.Symbol]
    masses: list[sp.Expr]            # one per particle
    positions: sp.Matrix             # nx
    fixed_point_positions: sp.Matrix  # dim per fixed point, stacked; functions of t only
    velocities: sp.Matrix            # nx: J v + X_t
    jacobian: sp.Matrix | None       # nx x nv (dX/dv); None for a looped tree (looped.py)
    bias_acceleration: sp.Matrix     # nx: gamma
    mass_matrix: sp.Matrix | None    # nv x nv, symmetric; None for a looped tree
    applied_forces: sp.Matrix        # nv: J^T F + generalized forces
    inertial_forces: sp.Matrix       # nv: -J^T M gamma
    generalized_forces: sp.Matrix    # nv: the part of applied_forces acting on q directly
    kinetic_energy: sp.Expr
    potential_energy: sp.Expr        # all of V
    generalized_potential: sp.Expr   # the part of V given with generalized forces
    linear_momentum: sp.Matrix       # dim
    angular_momentum: sp.Matrix      # 3 in 3D, 1 (the z component) in 2D
    inputs: list[sp.Symbol] = dataclasses.field(default_factory=list)  # the control inputs
    rates: sp.Matrix | None = None   # nq: q' = G(q) v
    constraints: "ConstraintDerivation | None" = None  # kinematic_constraints.py

    def residual(self) -> sp.Matrix:
        """Inverse-dynamics residual r(q, v, a, t) = Mt a - Ft - Fi (the force to apply)."""
        return self.mass_matrix * sp.Matrix(self.a) - self.applied_forces - self.inertial_forces


def _cross(a: sp.Matrix, b: sp.Matrix) -> sp.Matrix:
    if a.shape[0] == 3:
        return a.cross(b)
    return sp.Matrix([a[0] * b[1] - a[1] * b[0]])


def _times(matrix: sp.Matrix, vector: list[sp.Expr]) -> sp.Matrix:
    """matrix * vector, skipping zero entries (Jacobians of chains are half zeros)."""
    return sp.Matrix([sp.Add(*[matrix[i, j] * vector[j] for j in range(matrix.shape[1])
                               if matrix[i, j] != 0]) for i in range(matrix.shape[0])])


def bias_acceleration(xdot: sp.Matrix, q: list[sp.Symbol], rates: list[sp.Expr],
                      t: sp.Symbol) -> sp.Matrix:
    """gamma = d(xdot)/dq q' + d(xdot)/dt: the acceleration at v' = 0 (q' = v for ordinary
    coordinates, G(q) v for a free or ball joint's)."""
    return _times(termwise_jacobian(xdot, q), rates) + xdot.diff(t)


def _norm(d: sp.Matrix) -> sp.Expr:
    return sp.sqrt(sum(component**2 for component in d))


class _PerPoint(dict):
    """A point name -> value map that computes each value on its first lookup."""

    def __init__(self, compute: Callable[[str], sp.Matrix]):
        super().__init__()
        self._compute = compute

    def __missing__(self, name: str) -> sp.Matrix:
        value = self[name] = self._compute(name)
        return value


class Kinematics:
    """Positions and velocities of every point: X(q, t) and J v + X_t in reduced form.

    `jacobian` and `velocity` are computed per point on first use: a 1000-link chain's flat
    J has a million entries, and the checks of a tree need none of them (numeric_jacobian
    assembles J from the tree's joints).
    """

    def __init__(self, model: Model):
        self.q = [c.symbol for c in model.coordinates]
        self.v = [s.symbol for s in model.speeds]
        self.rates = model.coordinate_rates()  # q' = G(q) v
        # G, which takes dX/dq to J = dX/dv; None where q' = v
        self._rate_matrix = rate_matrix(model) if model.has_generalized_speeds else None
        self.t = model.time
        self.dim = model.dim
        self.particles = [p.name for p in model.particles]
        self.defaults = {p.symbol: sp.Float(p.default) for p in model.parameters}
        self._model = model
        self._tree: PointTree | None | Literal[False] = False   # False: not looked for yet
        self._numeric_jacobian: Callable[[list[float], float], list[list[float]]] | None = None
        self._numeric_joints: Callable[[list[float], float],
                                       list[list[list[float]]]] | None = None
        self._point_substitution: dict[sp.Symbol, sp.Expr] | None = None
        self.position: dict[str, sp.Matrix] = {p.name: p.position for p in model.points}
        self.jacobian: dict[str, sp.Matrix] = _PerPoint(
            lambda name: self.to_speeds(termwise_jacobian(self.position[name], self.q)))
        self.velocity: dict[str, sp.Matrix] = _PerPoint(
            lambda name: (_times(self.jacobian[name], self.v)
                          + self.position[name].diff(self.t)))

    def to_speeds(self, jacobian_q: sp.Matrix) -> sp.Matrix:
        """d/dv of what `jacobian_q` is d/dq of: times G."""
        return jacobian_q if self._rate_matrix is None else product(jacobian_q, self._rate_matrix)

    @property
    def tree(self) -> PointTree | None:
        """The model's tree of particles (point_tree.py), or None."""
        if self._tree is False:
            self._tree = point_tree(self._model)
        return self._tree

    @property
    def point_substitution(self) -> dict[sp.Symbol, sp.Expr]:
        """x / xdot symbols used in user force expressions -> their kinematic expressions."""
        if self._point_substitution is None:
            self._point_substitution = {}
            for point in self._model.points:
                self._point_substitution.update(zip(point.x, self.position[point.name]))
                self._point_substitution.update(zip(point.xdot, self.velocity[point.name]))
        return self._point_substitution

    def of(self, point: Point) -> tuple[sp.Matrix, sp.Matrix]:
        return self.position[point.name], self.velocity[point.name]

    def of_term(self, term: InertialTerm) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
        """(y, J_y, ydot) of an inertial term: a particle's as derived, a body's computed."""
        if term.name in self.position:
            return self.position[term.name], self.jacobian[term.name], self.velocity[term.name]
        jac = self.to_speeds(termwise_jacobian(term.position, self.q))
        return term.position, jac, _times(jac, self.v) + term.position.diff(self.t)

    def numeric_jacobian(self) -> Callable[[list[float], float], list[list[float]]]:
        """J(q, t) of the particles as floats, parameters at their defaults.

        Compiled once (the rank check and the singularity analysis share it), from its
        distinct nonzero entries only: a 100-link chain's J has 20000 entries, 200 distinct.
        A tree's J is assembled from its joints' (numeric_joint_jacobians): a particle's rows
        are its parent's plus its own joint's columns; a joint tree of bodies' from its links'
        frames and joint subspaces (body_jacobian.py).
        """
        if self._numeric_jacobian is None:
            bodies = body_tree(self._model) if self.tree is None else None
            if self.tree is not None:
                self._numeric_jacobian = self._tree_numeric_jacobian()
            elif bodies is not None:
                self._numeric_jacobian = numeric_body_jacobian(bodies, self.q, self.t,
                                                               self.defaults, self.particles)
            else:
                self._numeric_jacobian = self._flat_numeric_jacobian()
        return self._numeric_jacobian

    def numeric_joint_jacobians(self) -> Callable[[list[float], float], list[list[list[float]]]]:
        """For a tree: (q, t) -> per node, S_i = d offset_i / d q_i as dim rows of floats,
        one column per coordinate the node introduces, parameters at their defaults.

        J has full column rank exactly where every S_i has: J is block lower-triangular in
        the tree's order, with the S_i on its diagonal and a node's columns moving only the
        node and its descendants.
        """
        if self._numeric_joints is None:
            assert self.tree is not None  # called for a tree only
            nodes = self.tree.nodes
            entries = [entry.xreplace(self.defaults) for node in nodes
                       for entry in termwise_jacobian(node.offset,
                                                      [self.q[j] for j in node.coordinates])]
            values = sp.lambdify([self.q, self.t], entries, modules="math")
            shapes = [(self.dim, len(node.coordinates)) for node in nodes]

            def evaluate(q: list[float], t: float) -> list[list[list[float]]]:
                computed = iter([float(value) for value in values(q, t)])
                return [[[next(computed) for _ in range(columns)] for _ in range(rows)]
                        for rows, columns in shapes]
            self._numeric_joints = evaluate
        return self._numeric_joints

    def _tree_numeric_jacobian(self) -> Callable[[list[float], float], list[list[float]]]:
        assert self.tree is not None  # called for a tree only
        nodes = self.tree.nodes
        joints = self.numeric_joint_jacobians()
        row_of = {name: k for k, name in enumerate(self.particles)}
        nq = len(self.q)

        def evaluate(q: list[float], t: float) -> list[list[float]]:
            rows_of_node: list[list[list[float]]] = []
            for node, joint in zip(nodes, joints(q, t)):
                rows = ([[0.0] * nq for _ in range(self.dim)] if node.parent is None
                        else [list(row) for row in rows_of_node[node.parent]])
                for row, joint_row in zip(rows, joint):
                    for j, value in zip(node.coordinates, joint_row):
                        row[j] = value
                rows_of_node.append(rows)
            # every particle is a node: each slot is replaced below
            result: list[list[float]] = [[]] * (self.dim * len(self.particles))
            for node, rows in zip(nodes, rows_of_node):
                first = self.dim * row_of[node.particle.name]
                result[first:first + self.dim] = rows
            return result
        return evaluate

    def _flat_numeric_jacobian(self) -> Callable[[list[float], float], list[list[float]]]:
        jacobian = sp.Matrix.vstack(*[self.jacobian[name] for name in self.particles])
        rows, columns = jacobian.shape
        distinct: dict[sp.Expr, int] = {}
        where = [(i, j, distinct.setdefault(jacobian[i, j], len(distinct)))
                 for i in range(rows) for j in range(columns) if jacobian[i, j] != 0]
        # a body's entries share its rotations' products: compiled with one CSE over them
        values = sp.lambdify([self.q, self.t], [e.xreplace(self.defaults)
                                                for e in distinct], modules="math", cse=True)

        def evaluate(q: list[float], t: float) -> list[list[float]]:
            result = [[0.0] * columns for _ in range(rows)]
            computed = [float(value) for value in values(q, t)]
            for i, j, k in where:
                result[i][j] = computed[k]
            return result
        return evaluate


class PointKinematics(Protocol):
    """What forces and potentials read of a kinematics (Kinematics, and the named and the
    maximal ones): each point's position and velocity, and the point symbols' values."""
    @property
    def position(self) -> dict[str, sp.Matrix]: ...
    @property
    def point_substitution(self) -> dict[sp.Symbol, sp.Expr]: ...
    def of(self, point: Point) -> tuple[sp.Matrix, sp.Matrix]: ...


def particle_forces(model: Model, kin: PointKinematics, gravity: bool = True
                    ) -> dict[str, sp.Matrix]:
    """The x-space force on each particle, as expressions of `kin`'s variables.

    Gravity (unless `gravity` is False: the reduced derivation applies it at the inertial
    terms), springs, dampers and user forces; generalized forces act on q, not here.
    """
    zero = sp.zeros(model.dim, 1)
    force = {p.name: zero for p in model.particles}
    is_particle = set(force)

    def add(point: Point, f: sp.Matrix) -> None:
        for target, share in force_shares(point, f):
            if target.name in is_particle:  # fixed points' supports absorb their forces
                force[target.name] = force[target.name] + share

    for field in model.gravities if gravity else []:
        for p in model.particles:
            add(p, p.mass * field.acceleration)
    for s in model.springs:
        (xa, va), (xb, vb) = kin.of(s.a), kin.of(s.b)
        d = xb - xa
        length = _norm(d)
        direction = d / length
        magnitude = s.stiffness * (length - s.rest_length) / s.rest_length
        if s.damping != 0:
            magnitude += s.damping * dot(vb - va, direction) / s.rest_length
        add(s.b, -magnitude * direction)
        add(s.a, magnitude * direction)
    for damper in model.dampers:
        (_, va), (_, vb) = kin.of(damper.a), kin.of(damper.b)
        add(damper.b, -damper.coefficient * (vb - va))
        add(damper.a, damper.coefficient * (vb - va))
    for user in model.particle_forces:
        add(user.particle, user.force.xreplace(kin.point_substitution))
    return force


def x_space_potential(model: Model, kin: PointKinematics,
                      gravity_at: list[tuple[sp.Expr, sp.Matrix]] | None = None) -> sp.Expr:
    """Gravity, spring and user-force potentials; forces without a potential add nothing.

    Gravity acts on the particles, or on the (weight, position) pairs `gravity_at`."""
    potential = sp.Integer(0)
    if gravity_at is None:
        gravity_at = [(p.mass, kin.position[p.name]) for p in model.particles]
    for field in model.gravities:
        for weight, position in gravity_at:
            potential -= weight * dot(field.acceleration, position)
    for s in model.springs:
        stretch = _norm(kin.position[s.b.name] - kin.position[s.a.name]) - s.rest_length
        potential += s.stiffness * stretch**2 / (2 * s.rest_length)
    for user in model.particle_forces:
        if user.potential is not None:
            potential += user.potential.xreplace(kin.point_substitution)
    return potential


def generalized_potential(model: Model) -> sp.Expr:
    """The potentials given with generalized forces (joint springs), a function of q."""
    return sum((f.potential for f in model.generalized_forces if f.potential is not None),
               sp.Integer(0))


def fixed_point_positions(model: Model, kin: Kinematics) -> sp.Matrix:
    """The fixed points' positions, stacked (an empty column when the model has none)."""
    return sp.Matrix.vstack(sp.zeros(0, 1), *[kin.position[p.name] for p in model.fixed_points])


def gravity_force(model: Model, term: InertialTerm) -> sp.Matrix:
    """The force of every gravity field on a translational inertial term (else zero)."""
    force = sp.zeros(model.dim, 1)
    for field in model.gravities if term.translational else []:
        force += term.weight * field.acceleration
    return force


def derive(model: Model, kin: Kinematics | None = None) -> Derivation:
    """The reduced dynamics of `model`: Mt = J^T M J, Ft = J^T F, Fi = -J^T M gamma, energy,
    momenta and the Jacobians of the residual."""
    kin = kin or Kinematics(model)  # the pipeline builds it once for every stage
    nv = model.nv
    q, v, t = kin.q, kin.v, kin.t
    force = particle_forces(model, kin, gravity=False)

    mass_matrix = sp.zeros(nv, nv)
    applied = sp.zeros(nv, 1)
    inertial = sp.zeros(nv, 1)
    kinetic = sp.Integer(0)
    momentum = sp.zeros(model.dim, 1)
    angular = sp.zeros(3 if model.dim == 3 else 1, 1)
    gravity_at, gammas = [], {}
    for term in inertial_terms(model):
        y, jac, ydot = kin.of_term(term)
        w = term.weight
        gamma = gammas[term.name] = bias_acceleration(ydot, q, kin.rates, t)
        for a in range(nv):
            for b in range(a + 1):
                mass_matrix[a, b] += w * dot(jac[:, a], jac[:, b])
        applied += product(jac.T, gravity_force(model, term))
        inertial -= w * product(jac.T, gamma)
        kinetic += w * dot(ydot, ydot) / 2
        angular += w * _cross(y, ydot)
        if term.translational:
            momentum += w * ydot
            gravity_at.append((w, y))
    for a in range(nv):
        for b in range(a):
            mass_matrix[b, a] = mass_matrix[a, b]
    for p in model.particles:
        applied += product(kin.jacobian[p.name].T, force[p.name])
    generalized = generalized_force_vector(model, q)
    applied += generalized

    return Derivation(
        q=q, v=v, a=[s.acceleration for s in model.speeds],
        rates=sp.Matrix(kin.rates) if model.has_generalized_speeds else None, t=t,
        params=[prm.symbol for prm in model.parameters],
        inputs=[prm.symbol for prm in model.inputs],
        masses=[p.mass for p in model.particles],
        positions=sp.Matrix.vstack(*[kin.position[p.name] for p in model.particles]),
        fixed_point_positions=fixed_point_positions(model, kin),
        velocities=sp.Matrix.vstack(*[kin.velocity[p.name] for p in model.particles]),
        jacobian=sp.Matrix.vstack(*[kin.jacobian[p.name] for p in model.particles]),
        bias_acceleration=sp.Matrix.vstack(*[
            gammas[p.name] if p.name in gammas
            else bias_acceleration(kin.velocity[p.name], q, kin.rates, t)
            for p in model.particles]),
        mass_matrix=mass_matrix, applied_forces=applied, inertial_forces=inertial,
        generalized_forces=generalized,
        kinetic_energy=kinetic,
        potential_energy=(x_space_potential(model, kin, gravity_at)
                          + generalized_potential(model)),
        generalized_potential=generalized_potential(model),
        linear_momentum=momentum, angular_momentum=angular)
