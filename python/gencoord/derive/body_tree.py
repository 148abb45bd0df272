# SPDX-License-Identifier: BSD-3-Clause
"""The joint tree of a model built from links (joints.py, URDF), as the rigid-body recursions
walk it.

Each node is a link: its frame in its parent link's frame, T = (E, r) (E the child's axes in
the parent's, r the child's origin), a function of the joint's own coordinates; the joint's
motion subspace S and its velocity at zero rates sigma, in the link's axes, so that the
link's body-fixed velocity (omega; v), v the velocity of the link frame's origin, is

    V_i = X_i V_parent + S_i v_i + sigma_i,    X_i (omega; v) = (E^T omega, E^T (v + omega x r))

with v_i the joint's speeds: its coordinates' rates, or a ball or free joint's twist, for
which S is constant (speeds.py)
and its body's spatial inertia about the link origin in the link's axes. The tree is taken
from the links the model recorded, not read off expressions: a model qualifies when it is 3D,
every body is a link's body, no particle stands alone (bodies.py's point masses aside) and
every link moves by its own joint's coordinates only (no mimic joints).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from gencoord.dsl.frames import unskew
from gencoord.dsl.joints import Ball, Free, Link, Prismatic, Revolute
from gencoord.dsl.model import Model
from gencoord.dsl.items import BodyParticle
from gencoord.derive.tree_order import Tree


@dataclass
class BodyNode:
    link: Link
    parent: int | None           # index in BodyTree.nodes; None: the world
    coordinates: list[int]       # indices into model.coordinates this joint moves
    speeds: list[int]            # indices into model.speeds: v_i
    rates: list[sp.Expr]         # q_i' in terms of the speeds
    rotation: sp.Matrix          # E: the link's axes in its parent's
    translation: sp.Matrix       # r: the link's origin in its parent's axes
    subspace: sp.Matrix          # S: 6 x len(speeds), (angular; linear) in the link's axes
    drift: sp.Matrix             # sigma: the joint's velocity at zero rates (time-dependence)


@dataclass
class BodyTree(Tree):
    nodes: list[BodyNode]        # parents before children


def body_tree(model: Model) -> BodyTree | None:
    """The model's joint tree of bodies, or None when it has none the recursions can walk."""
    if model.dim != 3 or not model.links or not model.bodies:
        return None
    if any(not isinstance(p, BodyParticle) for p in model.particles):
        return None
    link_bodies = {id(link.body) for link in model.links if link.body is not None}
    if link_bodies != {id(body) for body in model.bodies}:
        return None
    q = [c.symbol for c in model.coordinates]
    index_of = {symbol: k for k, symbol in enumerate(q)}
    moved = [index_of[c] for link in model.links for c in link.coordinates]
    if sorted(moved) != list(range(len(q))):
        return None
    for link in model.links:  # a mimic joint moves by another joint's coordinate: no tree
        assert link.local is not None  # add_link and add_free_base set it
        moving = (link.local.rotation.free_symbols | link.local.origin.free_symbols) & set(q)
        if not moving <= set(link.coordinates):
            return None
    position_of = {id(link): k for k, link in enumerate(model.links)}
    speed_of = {speed.symbol: k for k, speed in enumerate(model.speeds)}
    rates = model.coordinate_rates()
    nodes = []
    for link in model.links:
        parent = None if link.parent is None else position_of[id(link.parent)]
        own = [q[index_of[c]] for c in link.coordinates]
        subspace, drift = _joint_motion(link, own, model.time)
        assert link.local is not None  # add_link and add_free_base set it
        nodes.append(BodyNode(link, parent, [index_of[c] for c in link.coordinates],
                              [speed_of[v] for v in link.speeds],
                              [rates[index_of[c]] for c in link.coordinates],
                              link.local.rotation, link.local.origin, subspace, drift))
    return BodyTree(nodes)


def _joint_motion(link: Link, own: list[sp.Symbol], t: sp.Symbol
                  ) -> tuple[sp.Matrix, sp.Matrix]:
    """S and sigma of the link's joint. A revolute joint turns about its axis, which the
    turn leaves fixed, and a prismatic one slides along it: S is the axis, exactly, and sigma
    is zero unless the joint's frame moves in time. Any other motion (a free base's
    translation and Euler angles, a joint whose origin moves in time) has (omega; v) =
    (unskew(E^T dE/dt), E^T dr/dt), simplified once per joint so S holds no cos^2 + sin^2."""
    zero = sp.zeros(3, 1)
    assert link.local is not None  # add_link and add_free_base set it
    rotation, origin = link.local.rotation, link.local.origin
    moves_in_time = t in rotation.free_symbols | origin.free_symbols
    if isinstance(link.joint, Free):  # speeds (v; omega), the twist in the link's axes
        return sp.Matrix.vstack(sp.Matrix.hstack(sp.zeros(3), sp.eye(3)),
                                sp.Matrix.hstack(sp.eye(3), sp.zeros(3))), sp.zeros(6, 1)
    if isinstance(link.joint, Ball):
        return sp.Matrix.vstack(sp.eye(3), sp.zeros(3)), sp.zeros(6, 1)
    if isinstance(link.joint, Revolute) and not moves_in_time:
        return sp.Matrix.vstack(link.joint.unit_axis(), zero), sp.zeros(6, 1)
    if isinstance(link.joint, Prismatic) and not moves_in_time:
        return sp.Matrix.vstack(zero, link.joint.unit_axis()), sp.zeros(6, 1)
    columns = []
    for coordinate in [*own, t]:
        spin = unskew((rotation.T * rotation.diff(coordinate)).applyfunc(sp.trigsimp))
        slide = (rotation.T * origin.diff(coordinate)).applyfunc(sp.trigsimp)
        columns.append(sp.Matrix.vstack(spin, slide))
    subspace = sp.Matrix.hstack(sp.zeros(6, 0), *columns[:-1])
    return subspace, columns[-1]
