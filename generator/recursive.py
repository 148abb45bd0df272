"""O(n) forward and inverse dynamics of a point-mass tree (point_tree.py), unrolled.

For a tree whose node i is a particle of mass m_i at X_i = X_parent + d_i(q_i, t), with
S_i = dd_i/dq_i (dim x k_i) and c_i the acceleration of d_i at qddot_i = 0:

    a_i = a_parent + S_i qddot_i + c_i          (a_root = -g)

Gravity g (the sum of the model's uniform fields) acts on every particle as m_i g, which is
the same as the fixed origin accelerating at -g with accelerations measured from free fall:
the recursions start from a_root = -g and leave gravity out of the forces f_i.

The force F_i the parent passes to subtree i through the massless link satisfies
tau_i = S_i^T F_i, where tau_i are the generalized forces on q_i.

Inverse dynamics (recursive Newton-Euler): a_i from the root out, then from the leaves in
F_i = m_i a_i - f_i + sum over children F_c; the residual r_i = S_i^T F_i - tau_i.

Forward dynamics (articulated-body recursion): from the leaves in, F_i = IA_i a_i + pA_i with

    IA_i = m_i 1 + sum_c (IA_c - U_c D_c^-1 U_c^T),   U = IA S,  D = S^T U
    pA_i = -f_i  + sum_c (pA_c + IA_c c_c + U_c D_c^-1 u_c),  u = tau - S^T (IA c + pA)

then from the root out qddot_i = D_i^-1 (u_i - U_i^T a_parent). Every matrix is dim x dim
or k x k, so each node costs a constant number of operations and the expressions stay small:
both the kernels and their generation grow like n, where J^T M J has n^2 entries and its
factorization n^3 / 6 steps. Every quantity is a named intermediate (structured.py).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from .derive import bias_acceleration, generalized_force_vector, particle_forces
from .model import Model
from .point_tree import PointTree
from .structured import Intermediates, NamedKinematics


@dataclass
class RecursiveDynamics:
    qddot: sp.Matrix                          # nq: articulated-body forward dynamics
    residual: sp.Matrix                       # nq: Newton-Euler r = Mt qdd - Ft - Fi
    definitions: list[tuple[sp.Symbol, sp.Expr]]


def spd_inverse(names: Intermediates, matrix: sp.Matrix) -> sp.Matrix:
    """The inverse of a small symmetric positive definite matrix of named entries."""
    if matrix.shape == (1, 1):
        return sp.Matrix([[names.name(1 / matrix[0, 0])]])
    inverse_det = names.name(1 / names.name(matrix.det(method="berkowitz")))
    return names.symmetric(matrix.adjugate() * inverse_det)


@dataclass
class _Joint:
    """One node's joint quantities, shared by both recursions."""
    coordinates: list[int]
    subspace: sp.Matrix      # S = dd/dq_i
    bias: sp.Matrix          # c: the acceleration of d at qddot_i = 0


def recursive_dynamics(model: Model, kin, tree: PointTree) -> RecursiveDynamics:
    """qddot by the articulated-body recursion and the residual by Newton-Euler."""
    names = Intermediates(prefix="__r")
    dim = model.dim
    q, v, t = kin.q, kin.v, kin.t
    qdd = [c.acceleration for c in model.coordinates]
    nodes, children = tree.nodes, tree.children()
    zero = sp.zeros(dim, 1)

    joints: list[_Joint] = []
    # the fixed points as derived, the particles from the recursion
    position = {p.name: kin.position[p.name] for p in model.fixed_points}
    velocity = {p.name: kin.velocity[p.name] for p in model.fixed_points}
    for node in nodes:
        own_q = [q[j] for j in node.coordinates]
        own_v = sp.Matrix(len(own_q), 1, [v[j] for j in node.coordinates])
        subspace = node.offset.jacobian(own_q) if own_q else sp.zeros(dim, 0)
        moving_frame = node.offset.diff(t)
        bias = bias_acceleration(subspace * own_v + moving_frame, own_q, list(own_v), t)
        joints.append(_Joint(node.coordinates, names.matrix(subspace), names.matrix(bias)))
        name = node.particle.name
        if node.parent is None:
            base_x, base_v = zero, zero
        else:
            parent = nodes[node.parent].particle.name
            base_x, base_v = position[parent], velocity[parent]
        position[name] = names.matrix(base_x + node.offset)
        velocity[name] = names.matrix(base_v + joints[-1].subspace * own_v + moving_frame)

    local = NamedKinematics(model, t, position, velocity)
    force = {name: names.matrix(f)
             for name, f in particle_forces(model, local, gravity=False).items()}
    gravity = sum((field.acceleration for field in model.gravities), zero)
    root = names.matrix(-gravity)
    tau = generalized_force_vector(model, q)
    joint_force = [names.matrix(sp.Matrix(len(joint.coordinates), 1,
                                          [tau[j] for j in joint.coordinates]))
                   for joint in joints]

    qddot = _articulated_body(names, nodes, children, joints, force, joint_force, root, qdd)
    residual = _newton_euler(names, nodes, children, joints, force, joint_force, root, qdd)
    return RecursiveDynamics(qddot, residual, names.definitions)


def _articulated_body(names, nodes, children, joints, force, joint_force, root, qdd
                      ) -> sp.Matrix:
    n, dim = len(nodes), root.shape[0]
    inertia: list[sp.Matrix] = [None] * n        # IA_i
    bias_force: list[sp.Matrix] = [None] * n     # pA_i
    passed: list[tuple] = [None] * n             # (Ia, pa) handed to the parent
    solve: list[tuple] = [None] * n              # (U, D^-1, u) for the outward pass
    for i in reversed(range(n)):
        node, joint = nodes[i], joints[i]
        IA = node.particle.mass * sp.eye(dim)
        pA = -force[node.particle.name]
        for c in children[i]:
            IA, pA = IA + passed[c][0], pA + passed[c][1]
        IA, pA = names.symmetric(IA), names.matrix(pA)
        inertia[i], bias_force[i] = IA, pA
        S, c_i = joint.subspace, joint.bias
        if S.shape[1] == 0:
            passed[i] = (IA, names.matrix(pA + IA * c_i))
            continue
        U = names.matrix(IA * S)
        D_inverse = spd_inverse(names, names.symmetric(S.T * U))
        u = names.matrix(joint_force[i] - S.T * (IA * c_i + pA))
        UD = names.matrix(U * D_inverse)
        passed[i] = (names.symmetric(IA - UD * U.T),
                     names.matrix(pA + IA * c_i + UD * u))
        solve[i] = (U, D_inverse, u)

    qddot = [sp.Integer(0)] * len(qdd)
    acceleration: list[sp.Matrix] = [None] * n
    for i, node in enumerate(nodes):
        base = root if node.parent is None else acceleration[node.parent]
        joint = joints[i]
        own = sp.zeros(0, 1)
        if solve[i] is not None:
            U, D_inverse, u = solve[i]
            own = names.matrix(D_inverse * (u - U.T * base))
            for j, value in zip(joint.coordinates, own):
                qddot[j] = value
        acceleration[i] = names.matrix(base + joint.subspace * own + joint.bias)
    return sp.Matrix(qddot)


def _newton_euler(names, nodes, children, joints, force, joint_force, root, qdd
                  ) -> sp.Matrix:
    n = len(nodes)
    acceleration: list[sp.Matrix] = [None] * n
    for i, node in enumerate(nodes):
        base = root if node.parent is None else acceleration[node.parent]
        joint = joints[i]
        own = sp.Matrix(len(joint.coordinates), 1, [qdd[j] for j in joint.coordinates])
        acceleration[i] = names.matrix(base + joint.subspace * own + joint.bias)
    residual = [sp.Integer(0)] * len(qdd)
    transmitted: list[sp.Matrix] = [None] * n
    for i in reversed(range(n)):
        node, joint = nodes[i], joints[i]
        F = node.particle.mass * acceleration[i] - force[node.particle.name]
        for c in children[i]:
            F = F + transmitted[c]
        transmitted[i] = names.matrix(F)
        for j, value in zip(joint.coordinates,
                            joint.subspace.T * transmitted[i] - joint_force[i]):
            residual[j] = names.name(value)
    return sp.Matrix(residual)
