# SPDX-License-Identifier: BSD-3-Clause
"""The motion of every link of a joint tree (body_tree.py), named link by link from the root.

Per link i, in its own axes (spatial.py): the body-fixed velocity V_i = X_i V_parent + V_J
with V_J = S qdot + sigma, the velocity-product acceleration

    c_i = dV_J/dt (at qddot = 0) + V_i x V_J

(the derivative of X_i V_parent is -V_J x X_i V_parent, and V_J x V_J = 0), so that the time
derivative of V_i is A_i = X_i A_parent + S_i qddot_i + c_i; the spatial inertia of its body
about the link origin; its axes and origin in the world's; and the positions and velocities
of the points on its body. The forces of springs, dampers and user forces on those points,
and body torques, become each link's external wrench. The recursions (body_recursion.py) and
the outputs that list points (positions, J, gamma) are written in these quantities.
"""

from __future__ import annotations

import sympy as sp

from gencoord.derive.body_tree import BodyTree
from gencoord.derive.dense import bias_acceleration, particle_forces
from gencoord.derive.speed_forces import coordinate_forces
from gencoord.dsl.model import Model
from gencoord.derive.spatial import cross_force, cross_motion, motion_to_child, rigid_inertia, split
from gencoord.derive.structured import Intermediates, NamedKinematics
from gencoord.symbolic.sums import product


class LinkKinematics:
    """Every link's frame, velocity, velocity-product acceleration and inertia, the points
    on its body, and the wrenches and joint forces that act; all named in `names`."""

    def __init__(self, model: Model, kin, tree: BodyTree, names: Intermediates):
        self.model, self.names = model, names
        self.nodes, self.children = tree.nodes, tree.children()
        q, v, self.t = kin.q, kin.v, kin.t
        n = len(self.nodes)
        self.rotation = [names.matrix(node.rotation) for node in self.nodes]
        self.translation = [names.matrix(node.translation) for node in self.nodes]
        self.velocity: list[sp.Matrix] = [None] * n
        self.bias: list[sp.Matrix] = [None] * n          # c_i
        self.joint_velocity: list[sp.Matrix] = [None] * n  # V_J
        self.joint_change: list[sp.Matrix] = [None] * n    # dV_J/dt at qddot = 0
        for i, node in enumerate(self.nodes):
            own_q = [q[j] for j in node.coordinates]
            own_v = sp.Matrix(len(node.speeds), 1, [v[j] for j in node.speeds])
            joint_velocity = product(node.subspace, own_v) + node.drift
            carried = (sp.zeros(6, 1) if node.parent is None else
                       self.to_child(i, self.velocity[node.parent]))
            self.velocity[i] = names.matrix(carried + joint_velocity)
            change = bias_acceleration(joint_velocity, own_q, node.rates, self.t)
            self.joint_velocity[i], self.joint_change[i] = joint_velocity, change
            self.bias[i] = names.matrix(change + cross_motion(self.velocity[i], joint_velocity))
        self.inertia = [self._link_inertia(node) for node in self.nodes]
        self.momentum_change = [names.matrix(cross_force(self.velocity[i],
                                                         self.inertia[i] * self.velocity[i]))
                                for i in range(n)]
        self.world_rotation, self.world_origin = self._world_frames()
        self.points, self.point_link = self._points()
        self.external = self._external_wrenches()
        self.tau = coordinate_forces(model)  # body torques enter as wrenches
        gravity = sum((field.acceleration for field in model.gravities), sp.zeros(3, 1))
        self.world = sp.Matrix.vstack(sp.zeros(3, 1), names.matrix(-gravity))  # A_world

    def to_child(self, i: int, motion: sp.Matrix) -> sp.Matrix:
        """X_i m: a motion of link i's parent in link i's axes."""
        return motion_to_child(self.rotation[i], self.translation[i], motion)

    def _link_inertia(self, node) -> sp.Matrix:
        link = node.link
        if link.body is None:
            return sp.zeros(6, 6)
        return self.names.symmetric(rigid_inertia(link.body.mass, link.inertial.origin,
                                                  self.inertia_at_centre(node)))

    @staticmethod
    def inertia_at_centre(node) -> sp.Matrix:
        """The body's inertia tensor about its centre of mass, in the link's axes."""
        inertial = node.link.inertial
        return product(product(inertial.rotation, node.link.body.inertia), inertial.rotation.T)

    def _world_frames(self) -> tuple[list[sp.Matrix], list[sp.Matrix]]:
        """Each link's axes and origin in the world's, composed from the root out."""
        names = self.names
        world_rotation, world_origin = [], []
        for i, node in enumerate(self.nodes):
            if node.parent is None:
                world_rotation.append(self.rotation[i])
                world_origin.append(self.translation[i])
                continue
            R, p = world_rotation[node.parent], world_origin[node.parent]
            world_rotation.append(names.matrix(product(R, self.rotation[i])))
            world_origin.append(names.matrix(p + product(R, self.translation[i])))
        return world_rotation, world_origin

    def _points(self) -> tuple[NamedKinematics, dict[str, tuple[int, sp.Matrix]]]:
        """Every point's position and velocity (a body's from its link's frame and velocity),
        and for those on bodies (link index, position in the link's axes)."""
        names = self.names
        position, velocity, point_link = {}, {}, {}
        for point in self.model.fixed_points:
            position[point.name] = point.position
            velocity[point.name] = point.position.diff(self.t)
        for i, node in enumerate(self.nodes):
            body = node.link.body
            if body is None:
                continue
            w, v = split(self.velocity[i])
            located = [(p.name, r) for p, r in zip(body.particles, body.offsets)]
            located += [(p.name, p.offset) for p in body.points]
            assert node.link.inertial is not None  # set with the link's body (joints.py)
            for name, r in located:
                rho = node.link.inertial.point(r)
                point_link[name] = (i, rho)
                position[name] = names.matrix(self.world_origin[i]
                                              + product(self.world_rotation[i], rho))
                velocity[name] = names.matrix(product(self.world_rotation[i], v + w.cross(rho)))
        return NamedKinematics(self.model, self.t, position, velocity), point_link

    def _external_wrenches(self) -> list[sp.Matrix]:
        """Each link's external wrench in its axes about its origin: body torques, and the
        forces of springs, dampers and user forces on its bodies' points."""
        model, names = self.model, self.names
        wrench = [sp.zeros(6, 1) for _ in self.nodes]
        link_of = {id(node.link.body): i for i, node in enumerate(self.nodes)
                   if node.link.body is not None}
        for item in model.torques:
            i = link_of[id(item.body)]
            wrench[i] += sp.Matrix.vstack(self.world_rotation[i].T * item.torque,
                                          sp.zeros(3, 1))
        if model.springs or model.dampers or model.particle_forces:
            for name, force in particle_forces(model, self.points, gravity=False).items():
                i, rho = self.point_link[name]
                in_link = names.matrix(self.world_rotation[i].T * force)
                wrench[i] += sp.Matrix.vstack(rho.cross(in_link), in_link)
        return [names.matrix(w) for w in wrench]
