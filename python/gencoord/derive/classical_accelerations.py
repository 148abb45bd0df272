# SPDX-License-Identifier: BSD-3-Clause
"""Newton-Euler's inputs in the classical acceleration of each link origin.

The spatial recursion (body_recursion.py) carries A_i, the time derivative of the body-fixed
velocity (omega; v), whose linear part is not the origin's acceleration but that minus
omega x v; its bias force V x* I V then needs every link's linear velocity v. Written in

    A'_i = A_i + (0; omega_i x v_i) = (omega_i'; the acceleration of link i's origin)

the body's equation of motion about its origin is F_i = I_i A'_i + (omega x I_o omega;
omega x (omega x h)), with I_o its rotational inertia about the origin and h = m c its first
moment, and A'_i follows from the parent's as

    A'_i = X_i (A'_p + (0; omega_p x (omega_p x r))) + S qddot + (dV_J/dt + omega_i x V_J)

for a joint that turns the link about an origin fixed in its parent (revolute and ball
joints: V_J has no linear part, so omega_i x V_J is (omega_i x omega_J; 0)). Neither needs a
linear velocity, which saves its propagation and the terms it brings, a sixth of an arm's
inverse dynamics. Other joints (prismatic, free, scripted) take the general form

    A'_i = X_i (A'_p - (0; omega_p x v_p)) + S qddot + c_i + (0; omega_i x v_i).

The world is at rest, so A'_world = A_world = (0; -g). The residual S^T F - tau is the same
number either way; only the intermediates differ.
"""

from __future__ import annotations

import sympy as sp

from gencoord.derive.body_kinematics import LinkKinematics
from gencoord.derive.spatial import split
from gencoord.dsl.frames import unskew
from gencoord.symbolic.sums import product


def classical_terms(links: LinkKinematics) -> list[tuple[sp.Matrix, sp.Matrix]]:
    """Per link, the terms A'_i adds to its parent's before the move to link i's axes, and
    after: A'_i = X_i (A'_p + before_i) + S qddot + after_i."""
    return [_classical_terms(links, i) for i in range(len(links.nodes))]


def classical_accelerations(links: LinkKinematics, terms, joint) -> list[sp.Matrix]:
    """A'_i from the root out, with A'_world = links.world; `terms` from classical_terms,
    joint_i S_i qddot_i or None."""
    result: list[sp.Matrix] = []
    for i, node in enumerate(links.nodes):
        base = links.world if node.parent is None else result[node.parent]
        before, after = terms[i]
        A = links.to_child(i, base + before) + after
        if joint[i] is not None:
            A += joint[i]
        result.append(links.names.matrix(A))
    return result


def classical_bias(links: LinkKinematics, terms) -> list[sp.Matrix]:
    """c'_i = X_i before_i + after_i, so that A'_i = X_i A'_p + S qddot + c'_i."""
    return [links.names.matrix(links.to_child(i, before) + after)
            for i, (before, after) in enumerate(terms)]


def _classical_terms(links: LinkKinematics, i: int) -> tuple[sp.Matrix, sp.Matrix]:
    """Link i's (before, after) of classical_terms."""
    node = links.nodes[i]
    w, v = split(links.velocity[i])
    V_J, change = links.joint_velocity[i], links.joint_change[i]
    if node.parent is None:
        parent_w, parent_v = sp.zeros(3, 1), sp.zeros(3, 1)
    else:
        parent_w, parent_v = split(links.velocity[node.parent])
    zero = sp.zeros(3, 1)
    if all(x == 0 for x in list(V_J[3:, 0]) + list(change[3:, 0])):
        r = links.translation[i]
        return (sp.Matrix.vstack(zero, parent_w.cross(parent_w.cross(r))),
                sp.Matrix.vstack(change[:3, 0] + w.cross(V_J[:3, 0]), zero))
    return (sp.Matrix.vstack(zero, -parent_w.cross(parent_v)),
            links.bias[i] + sp.Matrix.vstack(zero, w.cross(v)))


def classical_bias_forces(links: LinkKinematics) -> list[sp.Matrix]:
    """(omega x I_o omega; omega x (omega x h)) - f_i per link: F_i = I_i A'_i + this."""
    forces = []
    for i in range(len(links.nodes)):
        inertia = links.inertia[i]
        w = links.velocity[i][:3, 0]
        rotational, first_moment = inertia[:3, :3], unskew(inertia[:3, 3:])
        spin = links.names.matrix(product(rotational, w))
        turning = sp.Matrix.vstack(w.cross(spin), w.cross(w.cross(first_moment)))
        forces.append(links.names.matrix(turning - links.external[i]))
    return forces
