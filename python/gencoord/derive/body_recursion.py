# SPDX-License-Identifier: BSD-3-Clause
"""O(n) dynamics of a joint tree of rigid bodies (body_tree.py), unrolled over the links'
named motion (body_kinematics.py).

The body's equation of motion in its link's axes is F = I A + V x* I V, I its spatial
inertia about the link origin. Gravity enters as the world accelerating at -g
(A_world = (0; -g)), which is every body's weight at once. f_i are the external wrenches on
link i, tau_i the forces the model puts on its joint's coordinates.

- Inverse dynamics (recursive Newton-Euler): A_i from the root out; from the leaves in
  F_i = I_i A_i + V_i x* I_i V_i - f_i + sum over children X_c^T F_c, and the residual
  S_i^T F_i - tau_i.
- Forward dynamics (articulated-body algorithm): from the leaves in

      IA_i = I_i + sum_c X_c^T Ia_c X_c,       pA_i = V_i x* I_i V_i - f_i + sum_c X_c^T pa_c
      U = IA S, D = S^T U, u = tau - S^T pA,   Ia = IA - U D^-1 U^T, pa = pA + Ia c + U D^-1 u

  and from the root out qddot_i = D^-1 (u - U^T (X_i A_parent + c_i)).

  Both are unrolled in the classical accelerations of the link origins
  (classical_accelerations.py), whose c_i and V x* I V need no linear velocities; the residual
  and qddot are the same.
- The mass matrix (composite bodies): Ic_i = I_i + sum_c X_c^T Ic_c X_c; the block of
  coordinates j, i (j an ancestor of i, or i) is S_j^T (X^T Ic_i S_i), the force Ic_i S_i
  carried from link i to link j.
- Ft and Fi are Newton-Euler's residual at qddot = 0 split by what moves it: -Fi with the
  velocity terms alone (c_i, V x* I V), -Ft with gravity, the wrenches and tau alone.

The outputs that list points (positions, J, gamma), the energy and the momenta are read off
the same quantities, so every output of the derivation (derive/dense.py) comes out in O(n)
intermediates each; the outputs of n^2 entries (Mt, J) cost O(1) per entry.
"""

from __future__ import annotations

import sympy as sp

from gencoord.derive.body_kinematics import LinkKinematics
from gencoord.derive.body_tree import BodyTree
from gencoord.derive.classical_accelerations import (classical_accelerations, classical_bias,
                                                     classical_bias_forces, classical_terms)
from gencoord.derive.dense import (Derivation, fixed_point_positions, generalized_potential,
                                   x_space_potential)
from gencoord.derive.speed_forces import generalized_force_vector
from gencoord.dsl.model import Model
from gencoord.derive.point_recursion import RecursiveDynamics, place_symmetric, spd_inverse
from gencoord.derive.spatial import force_to_parent, inertia_to_parent, split
from gencoord.derive.structured import Intermediates
from gencoord.derive.tree_derivatives import analytic_residual_jacobians
from gencoord.symbolic.sums import product


def body_recursive_dynamics(model: Model, kin, tree: BodyTree, derivation: bool = True,
                            square_outputs: bool = True) -> RecursiveDynamics:
    """qddot by the articulated-body algorithm, the residual by Newton-Euler, and with
    `derivation` every other output, by composite bodies and Newton-Euler; without
    `square_outputs` no Mt or J (a looped tree's, looped.py)."""
    names = Intermediates(prefix="__r")
    links = LinkKinematics(model, kin, tree, names)
    qdd = [speed.acceleration for speed in model.speeds]
    nv = len(qdd)
    bias_force, terms = classical_bias_forces(links), classical_terms(links)
    qddot = _articulated_body(links, classical_bias(links, terms), bias_force, nv)
    joint = [node.subspace * sp.Matrix(len(node.speeds), 1, [qdd[j] for j in node.speeds])
             for node in tree.nodes]
    residual = _newton_euler(links, classical_accelerations(links, terms, joint), bias_force,
                             links.tau)
    # the closed form serves the unrolled kernels of a derived tree (a looped one differentiates
    # its products)
    jacobians = (analytic_residual_jacobians(model, links, kin.q, kin.v, qdd)
                 if derivation and square_outputs else None)
    return RecursiveDynamics(qddot, residual, names.definitions,
                             _derivation(model, kin, links, qdd, square_outputs)
                             if derivation else None, jacobians)


def _accelerations(links: LinkKinematics, world: sp.Matrix, with_bias: bool) -> list[sp.Matrix]:
    """A_i = X_i A_parent + c_i (c_i only `with_bias`) from A_world = `world`, at qddot = 0."""
    accelerations: list[sp.Matrix] = []
    for i, node in enumerate(links.nodes):
        base = world if node.parent is None else accelerations[node.parent]
        A = links.to_child(i, base)
        if with_bias:
            A += links.bias[i]
        accelerations.append(links.names.matrix(A))
    return accelerations


def _newton_euler(links: LinkKinematics, accelerations, bias_force, tau) -> sp.Matrix:
    """From the leaves in: F_i = I_i A_i + bias_force_i + the children's; S^T F - tau."""
    names, nodes = links.names, links.nodes
    residual = [sp.Integer(0)] * len(tau)
    transmitted: list[sp.Matrix] = [None] * len(nodes)
    for i in reversed(range(len(nodes))):
        F = product(links.inertia[i], accelerations[i]) + bias_force[i]
        for c in links.children[i]:
            F = F + force_to_parent(links.rotation[c], links.translation[c], transmitted[c])
        transmitted[i] = names.matrix(F)
        carried = product(nodes[i].subspace.T, transmitted[i])
        for j, value in zip(nodes[i].speeds, carried):
            residual[j] = names.name(value - tau[j])
    return sp.Matrix(residual)


def _articulated_body(links: LinkKinematics, bias, bias_force, nv: int) -> sp.Matrix:
    names, nodes = links.names, links.nodes
    n = len(nodes)
    passed: dict[int, tuple] = {}  # (Ia, pa) in the parent's axes
    solve: dict[int, tuple] = {}   # a moving joint's (U, D^-1, u), for the outward pass
    for i in reversed(range(n)):
        node = nodes[i]
        IA, pA = links.inertia[i], bias_force[i]
        for c in links.children[i]:
            IA, pA = IA + passed[c][0], pA + passed[c][1]
        IA, pA = names.symmetric(IA), names.matrix(pA)
        S = node.subspace
        if S.shape[1] == 0:
            Ia, pa = IA, names.matrix(pA + product(IA, bias[i]))
        else:
            U = names.matrix(product(IA, S))
            D_inverse = spd_inverse(names, names.symmetric(product(S.T, U)))
            own_tau = sp.Matrix([links.tau[j] for j in node.speeds])
            u = names.matrix(own_tau - product(S.T, pA))
            UD = names.matrix(product(U, D_inverse))
            Ia = names.symmetric(IA - product(UD, U.T))
            pa = names.matrix(pA + product(Ia, bias[i]) + product(UD, u))
            solve[i] = (U, D_inverse, u)
        if node.parent is not None:
            E, r = links.rotation[i], links.translation[i]
            passed[i] = (names.symmetric(inertia_to_parent(E, r, Ia, names)),
                         names.matrix(force_to_parent(E, r, pa)))

    qddot = [sp.Integer(0)] * nv
    acceleration: list[sp.Matrix] = [None] * n
    for i, node in enumerate(nodes):
        base = links.world if node.parent is None else acceleration[node.parent]
        before = names.matrix(links.to_child(i, base) + bias[i])
        if i not in solve:
            acceleration[i] = before
            continue
        U, D_inverse, u = solve[i]
        own = names.matrix(product(D_inverse, u - product(U.T, before)))
        for j, value in zip(node.speeds, own):
            qddot[j] = value
        acceleration[i] = names.matrix(before + product(node.subspace, own))
    return sp.Matrix(qddot)


def _composite_mass_matrix(links: LinkKinematics, nv: int) -> sp.Matrix:
    names, nodes = links.names, links.nodes
    n = len(nodes)
    composite: list[sp.Matrix] = [None] * n
    passed: list[sp.Matrix] = [None] * n
    for i in reversed(range(n)):
        total = links.inertia[i]
        for c in links.children[i]:
            total = total + passed[c]
        composite[i] = names.symmetric(total)
        if nodes[i].parent is not None:
            passed[i] = names.symmetric(inertia_to_parent(
                links.rotation[i], links.translation[i], composite[i], names))
    mass_matrix = sp.zeros(nv, nv)
    for i, node in enumerate(nodes):
        if not node.speeds:
            continue
        force = names.matrix(product(composite[i], node.subspace))
        place_symmetric(names, mass_matrix, node.speeds, node.speeds,
                        product(node.subspace.T, force))
        j = i
        while (parent := nodes[j].parent) is not None:
            E, r = links.rotation[j], links.translation[j]
            force = names.matrix(sp.Matrix.hstack(*[force_to_parent(E, r, force[:, k])
                                                    for k in range(force.shape[1])]))
            j = parent
            if nodes[j].speeds:
                place_symmetric(names, mass_matrix, nodes[j].speeds, node.speeds,
                                product(nodes[j].subspace.T, force))
    return mass_matrix


def _derivation(model: Model, kin, links: LinkKinematics, qdd, square_outputs: bool
                ) -> Derivation:
    """Every output of derive/dense.py, from the links' motion and the recursions; Mt and J only
    with `square_outputs`."""
    names, nodes = links.names, links.nodes
    nv = len(qdd)
    # gamma's accelerations: at qddot = 0 with the world at rest
    moving = _accelerations(links, sp.zeros(6, 1), True)
    inertial = -_newton_euler(links, moving, links.momentum_change, sp.zeros(nv, 1))
    applied = -_newton_euler(links, _accelerations(links, links.world, False),
                             [-wrench for wrench in links.external], links.tau)

    jacobians, gammas = {}, {}
    world_subspace = [names.matrix(sp.Matrix.vstack(links.world_rotation[i] * node.subspace[:3, :],
                                                    links.world_rotation[i] * node.subspace[3:, :]))
                      for i, node in enumerate(nodes)] if square_outputs else []
    kinetic, momentum, angular, gravity_at = sp.Integer(0), sp.zeros(3, 1), sp.zeros(3, 1), []
    for i, node in enumerate(nodes):
        body = node.link.body
        if body is None:
            continue
        assert node.link.inertial is not None  # set with the link's body (joints.py)
        R = links.world_rotation[i]
        w, v = split(links.velocity[i])
        dw, dv = split(moving[i])
        for particle in body.particles:
            _, rho = links.point_link[particle.name]
            gammas[particle.name] = names.matrix(
                R * (dv + dw.cross(rho) + w.cross(v + w.cross(rho))))
            if square_outputs:
                jacobians[particle.name] = _point_jacobian(
                    links, world_subspace, i, links.points.position[particle.name], nv)
        centre = links.world_origin[i] + R * node.link.inertial.origin
        centre_velocity = R * (v + w.cross(node.link.inertial.origin))
        kinetic += names.name((links.velocity[i].T * links.inertia[i] * links.velocity[i])[0] / 2)
        momentum += body.mass * centre_velocity
        angular += (body.mass * centre.cross(centre_velocity)
                    + R * (links.inertia_at_centre(node) * w))
        gravity_at.append((body.mass, centre))
    particles = model.particles
    return Derivation(
        q=kin.q, v=kin.v, a=qdd, t=kin.t, params=[p.symbol for p in model.parameters],
        inputs=[p.symbol for p in model.inputs],
        masses=[p.mass for p in particles],
        positions=sp.Matrix.vstack(*[links.points.position[p.name] for p in particles]),
        fixed_point_positions=fixed_point_positions(model, kin),
        velocities=sp.Matrix.vstack(*[links.points.velocity[p.name] for p in particles]),
        jacobian=(sp.Matrix.vstack(*[jacobians[p.name] for p in particles])
                  if square_outputs else None),
        bias_acceleration=sp.Matrix.vstack(*[gammas[p.name] for p in particles]),
        mass_matrix=_composite_mass_matrix(links, nv) if square_outputs else None,
        applied_forces=names.vector(applied), inertial_forces=names.vector(inertial),
        generalized_forces=generalized_force_vector(model, kin.q),
        kinetic_energy=kinetic,
        potential_energy=(x_space_potential(model, links.points, gravity_at)
                          + generalized_potential(model)),
        generalized_potential=generalized_potential(model),
        linear_momentum=momentum, angular_momentum=angular,
        rates=sp.Matrix(kin.rates) if model.has_generalized_speeds else None)


def _point_jacobian(links: LinkKinematics, world_subspace, i: int, x: sp.Matrix, nv: int
                    ) -> sp.Matrix:
    """dx/dq of a point at x on link i: each joint a on the way to the root moves it by its
    world motion (omega_a; v_a) as v_a + omega_a x (x - o_a)."""
    jacobian = sp.zeros(3, nv)
    a: int | None = i
    while a is not None:
        node = links.nodes[a]
        if node.speeds:
            arm = x - links.world_origin[a]
            for k, j in enumerate(node.speeds):
                spin, slide = split(world_subspace[a][:, k])
                jacobian[:, j] = slide + spin.cross(arm)
        a = node.parent
    return jacobian
