# SPDX-License-Identifier: BSD-3-Clause
"""dr/dq and dr/dv of Newton-Euler's residual for a tree of revolute and prismatic joints,
analytically, in world axes: O(n) spatial products and one or two dot products per entry.

Every spatial quantity here is in the world's axes about the world's origin (spatial.py's
conventions): joint i's axis S_i, link i's velocity v_i and acceleration a_i (gravity as the
world accelerating at -g), its body's inertia I_i and the force it needs,
f_i = I_i a_i + v_i x* I_i v_i, and the force F_i = sum of f_k over the subtree of i, so that
r_i = S_i^T F_i - tau_i. With p the parent of joint j,

    v_i = v_p + S_i qd_i,    a_i = a_p + S_i qdd_i + psi_i qd_i,    psi_i = v_p x S_i.

Turning joint j turns its subtree about S_j (or slides it along S_j): dS_i/dq_j = S_j x S_i
and dI_k/dq_j = S_j x* I_k - I_k S_j x for k in the subtree, while v_p and a_p stay. From that,
for k in the subtree of j,

    dv_k/dq_j = S_j x (v_k - v_p)         da_k/dq_j = S_j x (a_k - a_p) + psi_j x (v_k - v_p)
    dv_k/dqd_j = S_j                      da_k/dqd_j = S_j x v_k + 2 psi_j

and the force's derivative is the turned force plus what v_p and a_p, which do not turn, leave
over. With B_k w = v_k x* I_k w - I_k (v_k x w) + w x* I_k v_k (the derivative of the force
along a velocity w, less I_k's share of w's acceleration), summed over subtrees as the
composite IC_i and BC_i:

    dF_i/dq_j  = S_j x* F_i - IC_i alpha_j + BC_i psi_j,   alpha_j = S_j x a_p + psi_j x v_p
    dF_i/dqd_j = 2 IC_i psi_j + BC_i S_j

for i in the subtree of j. The turned force's share of dr_i/dq_j cancels against dS_i/dq_j,
so with gamma_i = IC_i S_i and beta_i = BC_i^T S_i, one row per joint, for j = i or an ancestor
of i

    dr_i/dq_j = -gamma_i . alpha_j + beta_i . psi_j,    dr_i/dv_j = 2 gamma_i . psi_j + beta_i . S_j

and for j below i (the subtree of j is in i's) dr_i/dq_j = S_i . Phi_j, dr_i/dv_j = S_i . Psi_j
with Phi_j and Psi_j the right-hand sides above at i = j. tau's own derivatives are
subtracted. B_k is K_k + H(I_k v_k) with K_k = v_k x* I_k - I_k v_k x = dI_k/dt and
H(h) w = w x* h, both linear in what the subtree sums: BC_i = K_i + H(hc_i), with K_i the
composite of dJ/dt and kappa = -dh/dt (K = [[dJ/dt, -[kappa]x], [[kappa]x, 0]]) and hc_i
that of the momenta I_k v_k.

This is the structure of the derivatives of Carpentier and Mansard (RSS 2018), derived here
for the generator's own conventions. Forward mode through the link-axes recursion carries each
direction through the joints below it instead, which is cheaper for short subtrees
(MIN_MEAN_SUBTREE).
"""

from __future__ import annotations

import sympy as sp

from gencoord.derive.body_kinematics import LinkKinematics
from gencoord.derive.body_tree import BodyNode
from gencoord.derive.spatial import cross_force, cross_motion, split
from gencoord.dsl.frames import skew
from gencoord.dsl.joints import Fixed, Prismatic, Revolute
from gencoord.dsl.model import Model
from gencoord.symbolic.sums import dot, product


# The closed form costs a constant per joint and a dot product or two per entry; forward mode
# costs each direction the joints below it, so the closed form pays where joints carry long
# subtrees. Operations of residual_jacobians (the `/// Ops:` line of the header that
# `./generate ROBOT.urdf` writes with MIN_MEAN_SUBTREE set to infinity and to 0), forward
# mode / closed form: models/iiwa14.urdf (a mean subtree of 4 joints) 7393 / 6249,
# models/ur5e.urdf (3.5) 4461 / 4603, tests/python/tree_models/branched_arm.urdf (2.4)
# 3607 / 4553, models/quadruped.urdf (2) 5215 / 7441.
MIN_MEAN_SUBTREE = 3.75


def analytic_residual_jacobians(model: Model, links: LinkKinematics, q: list[sp.Symbol],
                                v: list[sp.Symbol], qdd: list[sp.Symbol],
                                min_mean_subtree: float = MIN_MEAN_SUBTREE
                                ) -> tuple[sp.Matrix, sp.Matrix] | None:
    """(dr/dq, dr/dv) of Newton-Euler's residual, or None when the tree has a joint other than
    a revolute, prismatic or fixed one, motion in time or external wrenches, or joints that
    carry too few joints below them to gain (`min_mean_subtree`): forward mode through the
    recursion takes those."""
    if not _qualifies(model, links, min_mean_subtree):
        return None
    names, nodes = links.names, links.nodes
    world = _WorldMotion(links, v, qdd)
    rows, parts = _joint_terms(links, world)
    nv = len(v)
    dr_dq, dr_dv = sp.zeros(nv, len(q)), sp.zeros(nv, nv)
    for i, node in enumerate(nodes):
        if not node.speeds:
            continue
        (gamma, beta), (Phi, Psi) = rows[i], parts[i]
        row, column = node.speeds[0], node.coordinates[0]
        j: int | None = i
        while j is not None:  # joint j at or above i: entries (i, j), and (j, i) below j
            if nodes[j].speeds:
                S, psi, alpha = world.axis[j], world.psi[j], world.alpha[j]
                r, c = nodes[j].speeds[0], nodes[j].coordinates[0]
                dr_dq[row, c] = -dot(gamma, alpha) + dot(beta, psi)
                dr_dv[row, r] = 2 * dot(gamma, psi) + dot(beta, S)
                if j != i:
                    dr_dq[r, column] = dot(S, Phi)
                    dr_dv[r, row] = dot(S, Psi)
            j = nodes[j].parent
    tau = sp.Matrix(links.tau)
    dr_dq -= tau.jacobian(q)
    dr_dv -= tau.jacobian(v)
    return dr_dq.applyfunc(names.name), dr_dv.applyfunc(names.name)


def _joint_terms(links: LinkKinematics, world: "_WorldMotion") -> tuple[dict, dict]:
    """Per moving joint i, the rows (gamma_i, beta_i) and the columns' parts (Phi_i, Psi_i),
    from the subtrees' composites: the inertia (m, h, J), the force F, dJ/dt, kappa and hc."""
    names, nodes = links.names, links.nodes
    composite: list[tuple] = [()] * len(nodes)
    for i in reversed(range(len(nodes))):
        own = world.body_terms(i)
        for c in links.children[i]:
            own = tuple(a + b for a, b in zip(own, composite[c]))
        composite[i] = tuple(names.matrix(part) if isinstance(part, sp.MatrixBase)
                             else names.name(part) for part in own)
    rows, parts = {}, {}
    for i, node in enumerate(nodes):
        if not node.speeds:
            continue
        mass, moment, rotational, force, J_rate, kappa, momentum = composite[i]
        inertia = _SpatialInertia(mass, moment, rotational)
        B = _CompositeB(J_rate, kappa, momentum, names)
        S, psi, alpha = world.axis[i], world.psi[i], world.alpha[i]
        K_S, K_psi = B.symmetric_part(S), B.symmetric_part(psi)
        rows[i] = (names.matrix(inertia.times(S)), names.matrix(B.transposed_times(S, K_S)))
        parts[i] = (names.matrix(cross_force(S, force) - inertia.times(alpha)
                                 + B.times(psi, K_psi)),
                    names.matrix(2 * inertia.times(psi) + B.times(S, K_S)))
    return rows, parts


def _qualifies(model: Model, links: LinkKinematics, min_mean_subtree: float) -> bool:
    if model.has_generalized_speeds or any(any(w) for w in links.external):
        return False
    if _mean_subtree(links) < min_mean_subtree:
        return False
    t = links.t
    for node in links.nodes:
        joint = node.link.joint
        moving = isinstance(joint, (Revolute, Prismatic)) and len(node.speeds) == 1
        welded = (joint is None or isinstance(joint, Fixed)) and not node.speeds
        if not (moving or welded):
            return False
        if any(node.drift) or t in node.rotation.free_symbols | node.translation.free_symbols:
            return False
    return True


def _mean_subtree(links: LinkKinematics) -> float:
    """The mean over the moving joints of the number of moving joints at or below each."""
    nodes = links.nodes
    below = [1 if node.speeds else 0 for node in nodes]
    for i in reversed(range(len(nodes))):
        parent = nodes[i].parent
        if parent is not None:
            below[parent] += below[i]
    moving = [below[i] for i, node in enumerate(nodes) if node.speeds]
    return sum(moving) / len(moving) if moving else 0.0


class _SpatialInertia:
    """A spatial inertia about the world's origin as (m, h, J): m the mass, h = m c its first
    moment, J its rotational inertia about the origin; I (w; u) = (J w + h x u; m u - h x w)."""

    def __init__(self, mass, moment: sp.Matrix, rotational: sp.Matrix):
        self.mass, self.moment, self.rotational = mass, moment, rotational

    def times(self, motion: sp.Matrix) -> sp.Matrix:
        w, u = split(motion)
        h = self.moment
        return sp.Matrix.vstack(product(self.rotational, w) + h.cross(u),
                                self.mass * u - h.cross(w))


class _CompositeB:
    """B = K + H(hc) of a subtree, K = dI/dt = [[dJ/dt, -[kappa]x], [[kappa]x, 0]] (the
    file comment) kept as dJ/dt and kappa = -dh/dt; K x is shared by B x and B^T x."""

    def __init__(self, J_rate: sp.Matrix, kappa: sp.Matrix, momentum: sp.Matrix, names):
        self.J_rate, self.kappa, self.momentum, self.names = J_rate, kappa, momentum, names

    def symmetric_part(self, motion: sp.Matrix) -> sp.Matrix:
        """K x = (dJ/dt w - kappa x u; kappa x w) for x = (w; u)."""
        w, u = split(motion)
        return self.names.matrix(sp.Matrix.vstack(product(self.J_rate, w) - self.kappa.cross(u),
                                                  self.kappa.cross(w)))

    def times(self, motion: sp.Matrix, K_motion: sp.Matrix) -> sp.Matrix:
        return K_motion + cross_force(motion, self.momentum)

    def transposed_times(self, motion: sp.Matrix, K_motion: sp.Matrix) -> sp.Matrix:
        n, g = split(self.momentum)
        w, u = split(motion)
        # H(h)^T (w; u) = (n x w + g x u; g x w)
        return K_motion + sp.Matrix.vstack(n.cross(w) + g.cross(u), g.cross(w))


class _WorldMotion:
    """Each joint's axis S, psi and alpha and each link's velocity and acceleration, in world
    axes; and each body's inertia, force, dI/dt and momentum there (body_terms)."""

    def __init__(self, links: LinkKinematics, v: list[sp.Symbol], qdd: list[sp.Symbol]):
        self.links = links
        names, nodes = links.names, links.nodes
        n = len(nodes)
        self.axis: list[sp.Matrix] = [None] * n
        self.psi: list[sp.Matrix] = [None] * n
        self.alpha: list[sp.Matrix] = [None] * n
        self.velocity: list[sp.Matrix] = [None] * n
        self.acceleration: list[sp.Matrix] = [None] * n
        for i, node in enumerate(nodes):
            if node.parent is None:
                v_p, a_p = sp.zeros(6, 1), links.world
            else:
                v_p, a_p = self.velocity[node.parent], self.acceleration[node.parent]
            if not node.speeds:
                self.velocity[i], self.acceleration[i] = v_p, a_p
                continue
            S = self.axis[i] = names.matrix(_world_axis(node, links.world_rotation[i],
                                                        links.world_origin[i]))
            psi = self.psi[i] = names.matrix(cross_motion(v_p, S))
            self.alpha[i] = names.matrix(cross_motion(S, a_p) + cross_motion(psi, v_p))
            k = node.speeds[0]
            self.velocity[i] = names.matrix(v_p + S * v[k])
            self.acceleration[i] = names.matrix(a_p + S * qdd[k] + psi * v[k])

    def body_terms(self, i: int) -> tuple:
        """(m, h, J, f, dJ/dt, kappa = -dh/dt, I v) of link i's body in world axes; zeros
    without a body."""
        links, names = self.links, self.links.names
        node: BodyNode = links.nodes[i]
        body = node.link.body
        if body is None:
            return (sp.Integer(0), sp.zeros(3, 1), sp.zeros(3, 3), sp.zeros(6, 1),
                    sp.zeros(3, 3), sp.zeros(3, 1), sp.zeros(6, 1))
        R, p = links.world_rotation[i], links.world_origin[i]
        assert node.link.inertial is not None  # set with the link's body (joints.py)
        centre = names.matrix(p + product(R, node.link.inertial.origin))
        at_centre = product(product(R, links.inertia_at_centre(node)), R.T)
        m = body.mass
        J = names.symmetric(at_centre + m * (dot(centre, centre) * sp.eye(3)
                                             - product(centre, centre.T)))
        inertia = _SpatialInertia(m, names.matrix(m * centre), J)
        velocity, acceleration = self.velocity[i], self.acceleration[i]
        momentum = names.matrix(inertia.times(velocity))
        force = inertia.times(acceleration) + cross_force(velocity, momentum)
        # dI/dt = v x* I - I v x: dJ/dt = w x J - J w x - (h u^T + u h^T) + 2 (u . h) 1
        # and dh/dt = m u + w x h
        w, u = split(velocity)
        h = inertia.moment
        spin = product(skew(w), J)
        J_rate = names.symmetric(spin + spin.T - product(h, u.T) - product(u, h.T)
                                 + 2 * dot(u, h) * sp.eye(3))
        kappa = names.matrix(h.cross(w) - m * u)
        return m, h, J, force, J_rate, kappa, momentum


def _world_axis(node: BodyNode, R: sp.Matrix, origin: sp.Matrix) -> sp.Matrix:
    """The joint's S in world axes about the world's origin: a revolute joint's line through
    the link's origin, a prismatic joint's direction."""
    joint = node.link.joint
    assert isinstance(joint, (Revolute, Prismatic))  # _qualifies
    axis = product(R, joint.unit_axis())
    if isinstance(joint, Prismatic):
        return sp.Matrix.vstack(sp.zeros(3, 1), axis)
    return sp.Matrix.vstack(axis, origin.cross(axis))
