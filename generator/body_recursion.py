"""O(n) forward and inverse dynamics of a joint tree of rigid bodies (body_tree.py), unrolled.

Spatial vectors are 6 x 1, in each link's own axes: motions (omega; v), v the velocity of
the link origin, and forces (moment about the link origin; force). With the link's
body-fixed velocity V_i = X_i V_parent + V_J (body_tree.py), V_J = S qdot + sigma, the time
derivative of V_i is

    A_i = X_i A_parent + S_i qddot_i + c_i,    c_i = dV_J/dt (at qddot = 0) + V_i x V_J

(the derivative of X_i V_parent is -V_J x X_i V_parent, and V_J x V_J = 0), and the body's
equation of motion in these coordinates is F = I A + V x* I V, I its spatial inertia about the
link origin. Gravity enters as the world accelerating at -g (A_world = (0; -g)), which is every
body's weight at once.

Inverse dynamics (recursive Newton-Euler): A_i from the root out; from the leaves in,
F_i = I_i A_i + V_i x* I_i V_i - f_i + sum over children X_c^T F_c, and the residual
S_i^T F_i - tau_i. Forward dynamics (articulated-body algorithm): from the leaves in

    IA_i = I_i + sum_c X_c^T Ia_c X_c,       pA_i = V_i x* I_i V_i - f_i + sum_c X_c^T pa_c
    U = IA S, D = S^T U, u = tau - S^T pA,   Ia = IA - U D^-1 U^T, pa = pA + Ia c + U D^-1 u

and from the root out qddot_i = D^-1 (u - U^T (X_i A_parent + c_i)). f_i are the external
wrenches on link i (body torques, and the forces of springs, dampers and user forces on its
points), tau_i the generalized forces on its coordinates. Every quantity is a named
intermediate (structured.py), so both kernels and their generation grow like n.
"""

from __future__ import annotations

import sympy as sp

from .body_tree import BodyTree
from .derive import bias_acceleration, particle_forces
from .frames import skew
from .model import Model
from .recursive import RecursiveDynamics, named, named_symmetric, spd_inverse
from .structured import Intermediates, NamedKinematics


def _split(vector: sp.Matrix) -> tuple[sp.Matrix, sp.Matrix]:
    return vector[:3, 0], vector[3:, 0]


def motion_to_child(E: sp.Matrix, r: sp.Matrix, motion: sp.Matrix) -> sp.Matrix:
    """X m: a motion in the parent's axes at its origin, in the child's at the child's."""
    w, v = _split(motion)
    return sp.Matrix.vstack(E.T * w, E.T * (v + w.cross(r)))


def force_to_parent(E: sp.Matrix, r: sp.Matrix, force: sp.Matrix) -> sp.Matrix:
    """X^T f: a force in the child's axes about its origin, in the parent's about its own."""
    n, f = _split(force)
    f_parent = E * f
    return sp.Matrix.vstack(E * n + r.cross(f_parent), f_parent)


def cross_motion(V: sp.Matrix, motion: sp.Matrix) -> sp.Matrix:
    """V x m."""
    w, v = _split(V)
    w2, v2 = _split(motion)
    return sp.Matrix.vstack(w.cross(w2), w.cross(v2) + v.cross(w2))


def cross_force(V: sp.Matrix, force: sp.Matrix) -> sp.Matrix:
    """V x* f."""
    w, v = _split(V)
    n, f = _split(force)
    return sp.Matrix.vstack(w.cross(n) + v.cross(f), w.cross(f))


def inertia_to_parent(E: sp.Matrix, r: sp.Matrix, inertia: sp.Matrix) -> sp.Matrix:
    """X^T I X for a symmetric 6 x 6 I = [[A, B], [B^T, C]]: rotated into the parent's axes,
    then moved to its origin (blocks A + R B^T - B R - R C R, B + R C, C with R = [r]x)."""
    A, B, C = inertia[:3, :3], inertia[:3, 3:], inertia[3:, 3:]
    A, B, C = E * A * E.T, E * B * E.T, E * C * E.T
    R = skew(r)
    RC = R * C
    return sp.Matrix.vstack(
        sp.Matrix.hstack(A + R * B.T - B * R - RC * R, B + RC),
        sp.Matrix.hstack((B + RC).T, C))


def rigid_inertia(mass, com: sp.Matrix, inertia_at_com: sp.Matrix) -> sp.Matrix:
    """The spatial inertia about a frame's origin of a body of `mass` centred at `com`, with
    `inertia_at_com` about its centre of mass; all in that frame's axes."""
    C = skew(com)
    return sp.Matrix.vstack(
        sp.Matrix.hstack(inertia_at_com + mass * C * C.T, mass * C),
        sp.Matrix.hstack(mass * C.T, mass * sp.eye(3)))


def body_recursive_dynamics(model: Model, kin, tree: BodyTree) -> RecursiveDynamics:
    """qddot by the articulated-body algorithm and the residual by Newton-Euler."""
    names = Intermediates(prefix="__r")
    q, v, t = kin.q, kin.v, kin.t
    qdd = [c.acceleration for c in model.coordinates]
    nodes, children = tree.nodes, tree.children()
    n = len(nodes)

    rotation = [named(names, node.rotation) for node in nodes]
    translation = [named(names, node.translation) for node in nodes]
    velocity: list[sp.Matrix] = [None] * n
    bias: list[sp.Matrix] = [None] * n
    for i, node in enumerate(nodes):
        own_q = [q[j] for j in node.coordinates]
        own_v = sp.Matrix(len(own_q), 1, [v[j] for j in node.coordinates])
        joint_velocity = node.subspace * own_v + node.drift
        carried = (sp.zeros(6, 1) if node.parent is None else
                   motion_to_child(rotation[i], translation[i], velocity[node.parent]))
        velocity[i] = named(names, carried + joint_velocity)
        change = bias_acceleration(joint_velocity, own_q, list(own_v), t)
        bias[i] = named(names, change + cross_motion(velocity[i], joint_velocity))

    inertia = [_link_inertia(names, node) for node in nodes]
    momentum_change = [named(names, cross_force(velocity[i], inertia[i] * velocity[i]))
                       for i in range(n)]
    external = _external_wrenches(model, names, tree, rotation, translation, velocity, t)
    tau = _joint_forces(model, q)
    gravity = sum((field.acceleration for field in model.gravities), sp.zeros(3, 1))
    world = sp.Matrix.vstack(sp.zeros(3, 1), named(names, -gravity))

    ctx = (names, nodes, children, rotation, translation, bias, inertia, world)
    bias_force = [named(names, momentum_change[i] - external[i]) for i in range(n)]
    qddot = _articulated_body(ctx, bias_force, tau, len(qdd))
    residual = _newton_euler(ctx, bias_force, tau, qdd)
    return RecursiveDynamics(qddot, residual, names.definitions)


def _link_inertia(names: Intermediates, node) -> sp.Matrix:
    link = node.link
    if link.body is None:
        return sp.zeros(6, 6)
    body, inertial = link.body, link.inertial
    at_com = inertial.rotation * body.inertia * inertial.rotation.T
    return named_symmetric(names, rigid_inertia(body.mass, inertial.origin, at_com))


def _joint_forces(model: Model, q: list[sp.Symbol]) -> list[sp.Expr]:
    """The generalized forces acting on each coordinate (body torques are wrenches here)."""
    tau = [sp.Integer(0)] * len(q)
    for g in model.generalized_forces:
        tau[q.index(g.coordinate.symbol)] += g.force
    return tau


def _external_wrenches(model: Model, names: Intermediates, tree: BodyTree, rotation,
                       translation, velocity, t) -> list[sp.Matrix]:
    """Each link's external wrench in its axes about its origin: body torques, and the forces
    of springs, dampers and user forces on its bodies' points."""
    n = len(tree.nodes)
    wrench = [sp.zeros(6, 1) for _ in range(n)]
    if not (model.torques or model.springs or model.dampers or model.particle_forces):
        return wrench
    world_rotation, world_origin = _world_frames(names, tree, rotation, translation)
    link_of = {id(node.link.body): i for i, node in enumerate(tree.nodes)
               if node.link.body is not None}
    for item in model.torques:
        i = link_of[id(item.body)]
        wrench[i] += sp.Matrix.vstack(world_rotation[i].T * item.torque, sp.zeros(3, 1))

    if not (model.springs or model.dampers or model.particle_forces):
        return [named(names, w) for w in wrench]
    # every point's position and velocity from its link's frame and body-fixed velocity
    position, point_velocity, offset_of = {}, {}, {}
    for point in model.fixed_points:
        position[point.name] = point.position
        point_velocity[point.name] = point.position.diff(t)
    for i, node in enumerate(tree.nodes):
        body = node.link.body
        if body is None:
            continue
        inertial = node.link.inertial
        w, v = _split(velocity[i])
        located = [(p.name, r) for p, r in zip(body.particles, body.offsets)]
        located += [(p.name, p.offset) for p in body.points]
        for name, r in located:
            rho = inertial.point(r)
            offset_of[name] = (i, rho)
            position[name] = named(names, world_origin[i] + world_rotation[i] * rho)
            point_velocity[name] = named(names, world_rotation[i] * (v + w.cross(rho)))
    local = NamedKinematics(model, t, position, point_velocity)
    for name, force in particle_forces(model, local, gravity=False).items():
        i, rho = offset_of[name]
        in_link = named(names, world_rotation[i].T * force)
        wrench[i] += sp.Matrix.vstack(rho.cross(in_link), in_link)
    return [named(names, w) for w in wrench]


def _world_frames(names: Intermediates, tree: BodyTree, rotation, translation):
    """Each link's axes and origin in the world's, composed from the root out."""
    world_rotation, world_origin = [], []
    for i, node in enumerate(tree.nodes):
        if node.parent is None:
            world_rotation.append(rotation[i])
            world_origin.append(translation[i])
            continue
        R, p = world_rotation[node.parent], world_origin[node.parent]
        world_rotation.append(named(names, R * rotation[i]))
        world_origin.append(named(names, p + R * translation[i]))
    return world_rotation, world_origin


def _incoming(ctx, i: int, accelerations) -> sp.Matrix:
    """X_i A_parent: the parent's acceleration (the world's for a root) in link i's axes."""
    names, nodes, _, rotation, translation, _, _, world = ctx
    parent = nodes[i].parent
    base = world if parent is None else accelerations[parent]
    return named(names, motion_to_child(rotation[i], translation[i], base))


def _articulated_body(ctx, bias_force, tau, nq) -> sp.Matrix:
    names, nodes, children, rotation, translation, bias, inertia, _ = ctx
    n = len(nodes)
    passed: list[tuple] = [None] * n             # (Ia, pa) in the parent's axes
    solve: list[tuple] = [None] * n              # (U, D^-1, u) for the outward pass
    for i in reversed(range(n)):
        node = nodes[i]
        IA, pA = inertia[i], bias_force[i]
        for c in children[i]:
            IA, pA = IA + passed[c][0], pA + passed[c][1]
        IA, pA = named_symmetric(names, IA), named(names, pA)
        S = node.subspace
        if S.shape[1] == 0:
            Ia, pa = IA, named(names, pA + IA * bias[i])
        else:
            U = named(names, IA * S)
            D_inverse = spd_inverse(names, named_symmetric(names, S.T * U))
            own_tau = sp.Matrix([tau[j] for j in node.coordinates])
            u = named(names, own_tau - S.T * pA)
            UD = named(names, U * D_inverse)
            Ia = named_symmetric(names, IA - UD * U.T)
            pa = named(names, pA + Ia * bias[i] + UD * u)
            solve[i] = (U, D_inverse, u)
        if node.parent is not None:
            passed[i] = (named_symmetric(names, inertia_to_parent(rotation[i], translation[i],
                                                                  Ia)),
                         named(names, force_to_parent(rotation[i], translation[i], pa)))

    qddot = [sp.Integer(0)] * nq
    acceleration: list[sp.Matrix] = [None] * n
    for i, node in enumerate(nodes):
        before = named(names, _incoming(ctx, i, acceleration) + bias[i])
        if solve[i] is None:
            acceleration[i] = before
            continue
        U, D_inverse, u = solve[i]
        own = named(names, D_inverse * (u - U.T * before))
        for j, value in zip(node.coordinates, own):
            qddot[j] = value
        acceleration[i] = named(names, before + node.subspace * own)
    return sp.Matrix(qddot)


def _newton_euler(ctx, bias_force, tau, qdd) -> sp.Matrix:
    names, nodes, children, rotation, translation, bias, inertia, _ = ctx
    n = len(nodes)
    acceleration: list[sp.Matrix] = [None] * n
    for i, node in enumerate(nodes):
        own = sp.Matrix(len(node.coordinates), 1, [qdd[j] for j in node.coordinates])
        acceleration[i] = named(names, _incoming(ctx, i, acceleration)
                                + node.subspace * own + bias[i])
    residual = [sp.Integer(0)] * len(qdd)
    transmitted: list[sp.Matrix] = [None] * n
    for i in reversed(range(n)):
        node = nodes[i]
        F = inertia[i] * acceleration[i] + bias_force[i]
        for c in children[i]:
            F = F + force_to_parent(rotation[c], translation[c], transmitted[c])
        transmitted[i] = named(names, F)
        for j, value in zip(node.coordinates, node.subspace.T * transmitted[i]):
            residual[j] = names.name(value - tau[j])
    return sp.Matrix(residual)
