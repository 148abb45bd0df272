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
from .derive import bias_acceleration, coordinate_forces, particle_forces
from .frames import skew
from .model import Model
from .recursive import RecursiveDynamics, spd_inverse
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

    rotation = [names.matrix(node.rotation) for node in nodes]
    translation = [names.matrix(node.translation) for node in nodes]
    velocity: list[sp.Matrix] = [None] * n
    bias: list[sp.Matrix] = [None] * n
    for i, node in enumerate(nodes):
        own_q = [q[j] for j in node.coordinates]
        own_v = sp.Matrix(len(own_q), 1, [v[j] for j in node.coordinates])
        joint_velocity = node.subspace * own_v + node.drift
        carried = (sp.zeros(6, 1) if node.parent is None else
                   motion_to_child(rotation[i], translation[i], velocity[node.parent]))
        velocity[i] = names.matrix(carried + joint_velocity)
        change = bias_acceleration(joint_velocity, own_q, list(own_v), t)
        bias[i] = names.matrix(change + cross_motion(velocity[i], joint_velocity))

    inertia = [_link_inertia(names, node) for node in nodes]
    momentum_change = [names.matrix(cross_force(velocity[i], inertia[i] * velocity[i]))
                       for i in range(n)]
    external = _external_wrenches(model, names, tree, rotation, translation, velocity, t)
    tau = coordinate_forces(model, q)  # body torques enter as wrenches
    gravity = sum((field.acceleration for field in model.gravities), sp.zeros(3, 1))
    world = sp.Matrix.vstack(sp.zeros(3, 1), names.matrix(-gravity))

    ctx = (names, nodes, children, rotation, translation, bias, inertia, world)
    bias_force = [names.matrix(momentum_change[i] - external[i]) for i in range(n)]
    qddot = _articulated_body(ctx, bias_force, tau, len(qdd))
    residual = _newton_euler(ctx, bias_force, tau, qdd)
    return RecursiveDynamics(qddot, residual, names.definitions)


def _link_inertia(names: Intermediates, node) -> sp.Matrix:
    link = node.link
    if link.body is None:
        return sp.zeros(6, 6)
    body, inertial = link.body, link.inertial
    at_com = inertial.rotation * body.inertia * inertial.rotation.T
    return names.symmetric(rigid_inertia(body.mass, inertial.origin, at_com))


def _external_wrenches(model: Model, names: Intermediates, tree: BodyTree, rotation,
                       translation, velocity, t) -> list[sp.Matrix]:
    """Each link's external wrench in its axes about its origin: body torques, and the forces
    of springs, dampers and user forces on its bodies' points."""
    wrench = [sp.zeros(6, 1) for _ in tree.nodes]
    on_points = bool(model.springs or model.dampers or model.particle_forces)
    if not (model.torques or on_points):
        return wrench
    world_rotation, world_origin = _world_frames(names, tree, rotation, translation)
    link_of = {id(node.link.body): i for i, node in enumerate(tree.nodes)
               if node.link.body is not None}
    for item in model.torques:
        i = link_of[id(item.body)]
        wrench[i] += sp.Matrix.vstack(world_rotation[i].T * item.torque, sp.zeros(3, 1))
    if on_points:
        _add_point_forces(model, names, tree, world_rotation, world_origin, velocity, t, wrench)
    return [names.matrix(w) for w in wrench]


def _add_point_forces(model: Model, names: Intermediates, tree: BodyTree, world_rotation,
                      world_origin, velocity, t, wrench: list[sp.Matrix]) -> None:
    """Adds the forces on the bodies' points to their links' wrenches; the points' positions
    and velocities come from their link's frame and body-fixed velocity."""
    position, point_velocity, offset_of = {}, {}, {}
    for point in model.fixed_points:
        position[point.name] = point.position
        point_velocity[point.name] = point.position.diff(t)
    for i, node in enumerate(tree.nodes):
        body = node.link.body
        if body is None:
            continue
        w, v = _split(velocity[i])
        located = [(p.name, r) for p, r in zip(body.particles, body.offsets)]
        located += [(p.name, p.offset) for p in body.points]
        for name, r in located:
            rho = node.link.inertial.point(r)
            offset_of[name] = (i, rho)
            position[name] = names.matrix(world_origin[i] + world_rotation[i] * rho)
            point_velocity[name] = names.matrix(world_rotation[i] * (v + w.cross(rho)))
    local = NamedKinematics(model, t, position, point_velocity)
    for name, force in particle_forces(model, local, gravity=False).items():
        i, rho = offset_of[name]
        in_link = names.matrix(world_rotation[i].T * force)
        wrench[i] += sp.Matrix.vstack(rho.cross(in_link), in_link)


def _world_frames(names: Intermediates, tree: BodyTree, rotation, translation):
    """Each link's axes and origin in the world's, composed from the root out."""
    world_rotation, world_origin = [], []
    for i, node in enumerate(tree.nodes):
        if node.parent is None:
            world_rotation.append(rotation[i])
            world_origin.append(translation[i])
            continue
        R, p = world_rotation[node.parent], world_origin[node.parent]
        world_rotation.append(names.matrix(R * rotation[i]))
        world_origin.append(names.matrix(p + R * translation[i]))
    return world_rotation, world_origin


def _incoming(ctx, i: int, accelerations) -> sp.Matrix:
    """X_i A_parent: the parent's acceleration (the world's for a root) in link i's axes."""
    names, nodes, _, rotation, translation, _, _, world = ctx
    parent = nodes[i].parent
    base = world if parent is None else accelerations[parent]
    return names.matrix(motion_to_child(rotation[i], translation[i], base))


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
        IA, pA = names.symmetric(IA), names.matrix(pA)
        S = node.subspace
        if S.shape[1] == 0:
            Ia, pa = IA, names.matrix(pA + IA * bias[i])
        else:
            U = names.matrix(IA * S)
            D_inverse = spd_inverse(names, names.symmetric(S.T * U))
            own_tau = sp.Matrix([tau[j] for j in node.coordinates])
            u = names.matrix(own_tau - S.T * pA)
            UD = names.matrix(U * D_inverse)
            Ia = names.symmetric(IA - UD * U.T)
            pa = names.matrix(pA + Ia * bias[i] + UD * u)
            solve[i] = (U, D_inverse, u)
        if node.parent is not None:
            passed[i] = (names.symmetric(inertia_to_parent(rotation[i], translation[i], Ia)),
                         names.matrix(force_to_parent(rotation[i], translation[i], pa)))

    qddot = [sp.Integer(0)] * nq
    acceleration: list[sp.Matrix] = [None] * n
    for i, node in enumerate(nodes):
        before = names.matrix(_incoming(ctx, i, acceleration) + bias[i])
        if solve[i] is None:
            acceleration[i] = before
            continue
        U, D_inverse, u = solve[i]
        own = names.matrix(D_inverse * (u - U.T * before))
        for j, value in zip(node.coordinates, own):
            qddot[j] = value
        acceleration[i] = names.matrix(before + node.subspace * own)
    return sp.Matrix(qddot)


def _newton_euler(ctx, bias_force, tau, qdd) -> sp.Matrix:
    names, nodes, children, rotation, translation, bias, inertia, _ = ctx
    n = len(nodes)
    acceleration: list[sp.Matrix] = [None] * n
    for i, node in enumerate(nodes):
        own = sp.Matrix(len(node.coordinates), 1, [qdd[j] for j in node.coordinates])
        acceleration[i] = names.matrix(_incoming(ctx, i, acceleration)
                                       + node.subspace * own + bias[i])
    residual = [sp.Integer(0)] * len(qdd)
    transmitted: list[sp.Matrix] = [None] * n
    for i in reversed(range(n)):
        node = nodes[i]
        F = inertia[i] * acceleration[i] + bias_force[i]
        for c in children[i]:
            F = F + force_to_parent(rotation[c], translation[c], transmitted[c])
        transmitted[i] = names.matrix(F)
        for j, value in zip(node.coordinates, node.subspace.T * transmitted[i]):
            residual[j] = names.name(value - tau[j])
    return sp.Matrix(residual)
