# SPDX-License-Identifier: BSD-3-Clause
"""O(n) dynamics of a point-mass tree (point_tree.py), unrolled.

For a tree whose node i is a particle of mass m_i at X_i = X_parent + d_i(q_i, t), with
S_i = dd_i/dq_i (dim x k_i) and c_i the acceleration of d_i at qddot_i = 0:

    a_i = a_parent + S_i qddot_i + c_i          (a_root = -g)

Gravity g (the sum of the model's uniform fields) acts on every particle as m_i g, which is
the same as the fixed origin accelerating at -g with accelerations measured from free fall:
the recursions start from a_root = -g and leave gravity out of the forces f_i.

The force F_i the parent passes to subtree i through the massless link satisfies
tau_i = S_i^T F_i, where tau_i are the generalized forces on q_i.

- Inverse dynamics (recursive Newton-Euler): a_i from the root out, then from the leaves in
  F_i = m_i a_i - f_i + sum over children F_c; the residual r_i = S_i^T F_i - tau_i.
- Forward dynamics (articulated-body recursion): from the leaves in, F_i = IA_i a_i + pA_i with

      IA_i = m_i 1 + sum_c (IA_c - U_c D_c^-1 U_c^T),   U = IA S,  D = S^T U
      pA_i = -f_i  + sum_c (pA_c + IA_c c_c + U_c D_c^-1 u_c),  u = tau - S^T (IA c + pA)

  then from the root out qddot_i = D_i^-1 (u_i - U_i^T a_parent).
- The mass matrix (composite bodies): with M_i the mass of subtree i, the block of
  coordinates j, i (j an ancestor of i, or i) is M_i S_j^T S_i.
- Ft and Fi are Newton-Euler's residual at qddot = 0 split by what moves it: -Fi with the
  c_i alone, -Ft with gravity, the forces f_i and tau alone.

Every matrix is dim x dim or k x k, so each node costs a constant number of operations and
the expressions stay small: the kernels and their generation grow like n (the outputs of n^2
entries, Mt and J, by O(1) per entry), where J^T M J sums n terms per entry and its
factorization takes n^3 / 6 steps. Every quantity is a named intermediate (structured.py).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from gencoord.derive.dense import (Derivation, _cross, bias_acceleration, fixed_point_positions,
                                   generalized_potential, particle_forces, x_space_potential)
from gencoord.derive.speed_forces import generalized_force_vector
from gencoord.derive.differentiate import termwise_jacobian
from gencoord.dsl.model import Model
from gencoord.derive.point_tree import PointTree
from gencoord.symbolic.sums import dot, product
from gencoord.derive.structured import Intermediates, NamedKinematics


@dataclass
class RecursiveDynamics:
    qddot: sp.Matrix                          # nq: articulated-body forward dynamics
    residual: sp.Matrix                       # nq: Newton-Euler r = Mt qdd - Ft - Fi
    definitions: list[tuple[sp.Symbol, sp.Expr]]
    # every output of derive/dense.py, by the recursions (composite bodies for Mt), when asked for
    derivation: Derivation | None = None
    # (dr/dq, dr/dv) of the residual where a tree has them in closed form (tree_derivatives.py);
    # None: forward mode through the residual
    residual_jacobians: tuple[sp.Matrix, sp.Matrix] | None = None


# up to this size the adjugate over the determinant is cheapest; beyond it (a free joint's
# 6 x 6 articulated inertia: 36 determinants of 5 x 5) an LDL^T factorization is
ADJUGATE_MAX_SIZE = 3


def spd_inverse(names: Intermediates, matrix: sp.Matrix) -> sp.Matrix:
    """The inverse of a small symmetric positive definite matrix of named entries."""
    if matrix.shape == (1, 1):
        return sp.Matrix([[names.name(1 / matrix[0, 0])]])
    if matrix.shape[0] > ADJUGATE_MAX_SIZE:
        return _ldlt_inverse(names, matrix)
    inverse_det = names.name(1 / names.name(matrix.det(method="berkowitz")))
    return names.symmetric(matrix.adjugate() * inverse_det)


def _ldlt_inverse(names: Intermediates, matrix: sp.Matrix) -> sp.Matrix:
    """A^-1 = L^-T D^-1 L^-1 from A = L D L^T (L unit lower triangular), every entry named;
    about n^3 / 2 operations."""
    n = matrix.shape[0]
    lower, scaled = sp.eye(n), sp.zeros(n, n)  # scaled[i, k] = L[i, k] D[k]
    pivot, inverse_pivot = [sp.Integer(0)] * n, [sp.Integer(0)] * n
    for j in range(n):
        pivot[j] = names.name(matrix[j, j] - sum((lower[j, k] * scaled[j, k] for k in range(j)),
                                                 sp.Integer(0)))
        inverse_pivot[j] = names.name(1 / pivot[j])
        for i in range(j + 1, n):
            scaled[i, j] = names.name(matrix[i, j] - sum((lower[i, k] * scaled[j, k]
                                                          for k in range(j)), sp.Integer(0)))
            lower[i, j] = names.name(scaled[i, j] * inverse_pivot[j])
    lower_inverse = sp.eye(n)  # L^-1, unit lower triangular, by forward substitution
    for i in range(n):
        for j in range(i):
            lower_inverse[i, j] = names.name(-sum((lower[i, k] * lower_inverse[k, j]
                                                   for k in range(j, i)), sp.Integer(0)))
    result = sp.zeros(n, n)
    for i in range(n):
        for j in range(i + 1):
            result[i, j] = result[j, i] = names.name(sum(
                (lower_inverse[k, i] * lower_inverse[k, j] * inverse_pivot[k]
                 for k in range(i, n)), sp.Integer(0)))
    return result


def place_symmetric(names: Intermediates, matrix: sp.Matrix, rows: list[int],
                    columns: list[int], block: sp.Matrix) -> None:
    """Names the block of `matrix` at (rows, columns) and mirrors it; of a diagonal block
    (rows == columns) only the lower triangle is computed."""
    for a, row in enumerate(rows):
        for b, column in enumerate(columns):
            if rows == columns and b > a:
                break
            matrix[row, column] = matrix[column, row] = names.name(block[a, b])


@dataclass
class _Joint:
    """One node's joint quantities, shared by the recursions."""
    coordinates: list[int]
    subspace: sp.Matrix      # S = dd/dq_i
    bias: sp.Matrix          # c: the acceleration of d at qddot_i = 0


def recursive_dynamics(model: Model, kin, tree: PointTree, derivation: bool = True,
                       square_outputs: bool = True) -> RecursiveDynamics:
    """qddot by the articulated-body recursion, the residual by Newton-Euler, and with
    `derivation` every other output, by composite masses and Newton-Euler; without
    `square_outputs` no Mt or J (a looped tree's, looped.py)."""
    names = Intermediates(prefix="__r")
    zero = sp.zeros(model.dim, 1)
    qdd = [c.acceleration for c in model.coordinates]
    joints, position, velocity = _joint_motions(model, kin, tree, names)
    local = NamedKinematics(model, kin.t, position, velocity)
    force = [names.matrix(f) for f in _node_forces(model, local, tree.nodes)]
    gravity = sum((field.acceleration for field in model.gravities), zero)
    root = names.matrix(-gravity)
    tau = generalized_force_vector(model, kin.q)
    ctx = (names, tree.nodes, tree.children(), joints)

    qddot = _articulated_body(ctx, force, tau, root)
    joint = [product(joint.subspace,
                     sp.Matrix(len(joint.coordinates), 1, [qdd[j] for j in joint.coordinates]))
             for joint in joints]
    residual = _newton_euler(ctx, _accelerations(ctx, root, joint, True), force, tau)
    if not derivation:
        return RecursiveDynamics(qddot, residual, names.definitions)
    derived = _derivation(model, kin, tree, ctx, local, (force, tau, root), square_outputs)
    return RecursiveDynamics(qddot, residual, names.definitions, derived)


def _joint_motions(model: Model, kin, tree: PointTree, names: Intermediates):
    """Each node's joint (S, c), and every point's position and velocity: the fixed points
    as derived, the particles from the recursion."""
    q, v, t = kin.q, kin.v, kin.t
    nodes, zero = tree.nodes, sp.zeros(model.dim, 1)
    joints: list[_Joint] = []
    position = {p.name: kin.position[p.name] for p in model.fixed_points}
    velocity = {p.name: kin.velocity[p.name] for p in model.fixed_points}
    for node in nodes:
        own_q = [q[j] for j in node.coordinates]
        own_v = sp.Matrix(len(own_q), 1, [v[j] for j in node.coordinates])
        subspace = termwise_jacobian(node.offset, own_q) if own_q else sp.zeros(model.dim, 0)
        moving_frame = node.offset.diff(t)
        bias = bias_acceleration(product(subspace, own_v) + moving_frame, own_q, list(own_v), t)
        joints.append(_Joint(node.coordinates, names.matrix(subspace), names.matrix(bias)))
        name = node.particle.name
        if node.parent is None:
            base_x, base_v = zero, zero
        else:
            parent = nodes[node.parent].particle.name
            base_x, base_v = position[parent], velocity[parent]
        position[name] = names.matrix(base_x + node.offset)
        velocity[name] = names.matrix(base_v + product(joints[-1].subspace, own_v) + moving_frame)
    return joints, position, velocity


def _derivation(model: Model, kin, tree: PointTree, ctx, local: NamedKinematics, loads,
                square_outputs: bool) -> Derivation:
    """Every output besides qddot and the residual: Fi and gamma from the velocity terms
    alone, Ft from the forces alone (`loads`: each node's force, tau and the root's
    acceleration), Mt by composite masses."""
    names, nodes, _, joints = ctx
    force, tau, root = loads
    position, velocity = local.position, local.velocity
    zero, nq, particles = sp.zeros(model.dim, 1), len(kin.q), model.particles
    moving = _accelerations(ctx, zero, [None] * len(nodes), True)
    inertial = -_newton_euler(ctx, moving, [zero] * len(nodes), sp.zeros(nq, 1))
    applied = -_newton_euler(ctx, _accelerations(ctx, root, [None] * len(nodes), False),
                             force, tau)
    gamma_of = {node.particle.name: moving[i] for i, node in enumerate(nodes)}
    return Derivation(
        q=kin.q, v=kin.v, a=[s.acceleration for s in model.speeds], t=kin.t,
        params=[p.symbol for p in model.parameters],
        inputs=[p.symbol for p in model.inputs],
        masses=[p.mass for p in particles],
        positions=sp.Matrix.vstack(*[position[p.name] for p in particles]),
        fixed_point_positions=fixed_point_positions(model, kin),
        velocities=sp.Matrix.vstack(*[velocity[p.name] for p in particles]),
        jacobian=(sp.Matrix.vstack(*[_particle_jacobian(tree, joints, i, nq)
                                     for i in _node_order(tree, particles)])
                  if square_outputs else None),
        bias_acceleration=sp.Matrix.vstack(*[gamma_of[p.name] for p in particles]),
        mass_matrix=_composite_mass_matrix(ctx, nq) if square_outputs else None,
        applied_forces=names.vector(applied), inertial_forces=names.vector(inertial),
        generalized_forces=tau,
        kinetic_energy=sum((names.name(p.mass * dot(velocity[p.name], velocity[p.name]) / 2)
                            for p in particles), sp.Integer(0)),
        potential_energy=x_space_potential(model, local) + generalized_potential(model),
        generalized_potential=generalized_potential(model),
        linear_momentum=sum((p.mass * velocity[p.name] for p in particles), zero),
        angular_momentum=sum((p.mass * _cross(position[p.name], velocity[p.name])
                              for p in particles), sp.zeros(3 if model.dim == 3 else 1, 1)))


def _node_forces(model: Model, local: NamedKinematics, nodes) -> list[sp.Matrix]:
    """f_i: the forces on each node's particle, gravity aside."""
    force = particle_forces(model, local, gravity=False)
    return [force[node.particle.name] for node in nodes]


def _node_order(tree: PointTree, particles) -> list[int]:
    """The node of each particle, in the model's particle order."""
    node_of = {node.particle.name: i for i, node in enumerate(tree.nodes)}
    return [node_of[p.name] for p in particles]


def _particle_jacobian(tree: PointTree, joints: list[_Joint], i: int, nq: int) -> sp.Matrix:
    """dX_i/dq: S_a in the columns of every node a from i to the root."""
    jacobian = sp.zeros(joints[i].subspace.shape[0], nq)
    a: int | None = i
    while a is not None:
        for k, j in enumerate(joints[a].coordinates):
            jacobian[:, j] = joints[a].subspace[:, k]
        a = tree.nodes[a].parent
    return jacobian


def _accelerations(ctx, root: sp.Matrix, joint, with_bias: bool) -> list[sp.Matrix]:
    """a_i = a_parent + joint_i + c_i (c_i only `with_bias`) from a_root = `root`; joint_i
    is S_i qddot_i, or None for zero."""
    names, nodes, _, joints = ctx
    accelerations: list[sp.Matrix] = []
    for i, node in enumerate(nodes):
        a = root if node.parent is None else accelerations[node.parent]
        if joint[i] is not None:
            a = a + joint[i]
        if with_bias:
            a = a + joints[i].bias
        accelerations.append(names.matrix(a))
    return accelerations


def _newton_euler(ctx, accelerations, force, tau) -> sp.Matrix:
    """From the leaves in: F_i = m_i a_i - force_i + the children's; S^T F - tau."""
    names, nodes, children, joints = ctx
    residual = [sp.Integer(0)] * len(tau)
    transmitted: list[sp.Matrix] = [None] * len(nodes)
    for i in reversed(range(len(nodes))):
        F = nodes[i].particle.mass * accelerations[i] - force[i]
        for c in children[i]:
            F = F + transmitted[c]
        transmitted[i] = names.matrix(F)
        carried = product(joints[i].subspace.T, transmitted[i])
        for j, value in zip(joints[i].coordinates, carried):
            residual[j] = names.name(value - tau[j])
    return sp.Matrix(residual)


def _articulated_body(ctx, force, tau, root) -> sp.Matrix:
    names, nodes, children, joints = ctx
    n, dim = len(nodes), root.shape[0]
    passed: dict[int, tuple] = {}  # (Ia, pa) handed to the parent
    solve: dict[int, tuple] = {}   # a moving joint's (U, D^-1, u), for the outward pass
    for i in reversed(range(n)):
        node, joint = nodes[i], joints[i]
        IA = node.particle.mass * sp.eye(dim)
        pA = -force[i]
        for c in children[i]:
            IA, pA = IA + passed[c][0], pA + passed[c][1]
        IA, pA = names.symmetric(IA), names.matrix(pA)
        S, c_i = joint.subspace, joint.bias
        if S.shape[1] == 0:
            passed[i] = (IA, names.matrix(pA + product(IA, c_i)))
            continue
        U = names.matrix(product(IA, S))
        D_inverse = spd_inverse(names, names.symmetric(product(S.T, U)))
        own_tau = sp.Matrix([tau[j] for j in joint.coordinates])
        u = names.matrix(own_tau - product(S.T, product(IA, c_i) + pA))
        UD = names.matrix(product(U, D_inverse))
        passed[i] = (names.symmetric(IA - product(UD, U.T)),
                     names.matrix(pA + product(IA, c_i) + product(UD, u)))
        solve[i] = (U, D_inverse, u)

    qddot = [sp.Integer(0)] * len(tau)
    acceleration: list[sp.Matrix] = [None] * n
    for i, node in enumerate(nodes):
        base = root if node.parent is None else acceleration[node.parent]
        joint = joints[i]
        own = sp.zeros(0, 1)
        if i in solve:
            U, D_inverse, u = solve[i]
            own = names.matrix(product(D_inverse, u - product(U.T, base)))
            for j, value in zip(joint.coordinates, own):
                qddot[j] = value
        acceleration[i] = names.matrix(base + product(joint.subspace, own) + joint.bias)
    return sp.Matrix(qddot)


def _composite_mass_matrix(ctx, nq: int) -> sp.Matrix:
    names, nodes, children, joints = ctx
    subtree_mass: list[sp.Expr] = [None] * len(nodes)
    for i in reversed(range(len(nodes))):
        subtree_mass[i] = names.name(nodes[i].particle.mass
                                     + sum((subtree_mass[c] for c in children[i]), 0))
    mass_matrix = sp.zeros(nq, nq)
    for i, joint in enumerate(joints):
        if not joint.coordinates:
            continue
        carried = names.matrix(subtree_mass[i] * joint.subspace)
        a = i
        while a is not None:
            if joints[a].coordinates:
                place_symmetric(names, mass_matrix, joints[a].coordinates, joint.coordinates,
                                product(joints[a].subspace.T, carried))
            a = nodes[a].parent
    return mass_matrix
