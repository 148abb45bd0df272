# SPDX-License-Identifier: BSD-3-Clause
"""Finds the kinematic tree of a point-mass model, which the recursive kernels walk.

A model of particles is a translational tree when each particle's position is its parent's
plus an offset in coordinates of its own:

    X_i(q, t) = X_parent(i)(q, t) + d_i(q_i, t)

where the q_i of different particles are disjoint and a root particle's parent is the fixed
origin. The n-link chain (each bob the previous one plus a link in one new angle) is one; so
is a branched pendulum or a chain of spherical pendulums. Nothing is assumed of how the model
file was written: the tree is read off the expressions, and a model that is not such a tree
(a particle moved by its parent's coordinates other than through the parent, or bodies)
gets None and keeps the dense kernels.

For each coordinate, the particle that introduces it is the one with the fewest coordinates
among those that depend on it; the parent of a particle is the particle whose coordinates are
exactly the rest, and the difference of their positions must involve only the new ones.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from gencoord.dsl.model import Model

from gencoord.dsl.items import Particle
from gencoord.symbolic.sums import difference
from gencoord.derive.tree_order import Tree


@dataclass
class TreeNode:
    particle: Particle
    parent: int | None           # index in PointTree.nodes; None: the fixed origin
    coordinates: list[int]       # indices into model.coordinates this node introduces
    offset: sp.Matrix            # d = X_particle - X_parent, a function of those and t


@dataclass
class PointTree(Tree):
    nodes: list[TreeNode]        # parents before children


def point_tree(model: Model) -> PointTree | None:
    """The model's translational tree of particles, or None when it has none."""
    if model.bodies or not model.particles:
        return None
    q = [c.symbol for c in model.coordinates]
    index_of = {symbol: k for k, symbol in enumerate(q)}
    particles = model.particles
    depends = [frozenset(p.position.free_symbols & index_of.keys()) for p in particles]

    owner: dict[sp.Symbol, int] = {}
    for k, coordinates in enumerate(depends):
        for c in coordinates:
            if c not in owner or len(coordinates) < len(depends[owner[c]]):
                owner[c] = k
    if len(owner) != len(q):
        return None  # a coordinate that moves no particle
    introduces: list[set] = [set() for _ in particles]
    for c, k in owner.items():
        introduces[k].add(c)

    with_coordinates: dict[frozenset, list[int]] = {}
    for k, coordinates in enumerate(depends):
        with_coordinates.setdefault(coordinates, []).append(k)

    order = sorted(range(len(particles)), key=lambda k: (len(depends[k]), k))
    parents: dict[int, int | None] = {}
    offsets: dict[int, sp.Matrix] = {}
    for k in order:
        rest = depends[k] - introduces[k]
        if not rest:
            parent, offset = None, particles[k].position
        else:
            # a particle introducing nothing hangs from one before it (no cycles)
            candidates = [a for a in with_coordinates.get(rest, ())
                          if a != k and (introduces[k] or a < k)]
            differences = ((a, difference(particles[k].position, particles[a].position))
                           for a in candidates)
            parent, offset = next(((a, offset) for a, offset in differences
                                   if _moves_only_with(offset, introduces[k], index_of)),
                                  (None, None))
            if offset is None:
                return None
        parents[k], offsets[k] = parent, offset

    position_in = {k: i for i, k in enumerate(order)}
    nodes = [TreeNode(particles[k],
                      None if (parent := parents[k]) is None else position_in[parent],
                      sorted(index_of[c] for c in introduces[k]), offsets[k])
             for k in order]
    return PointTree(nodes)


def _moves_only_with(offset: sp.Matrix, coordinates: set, index_of: dict) -> bool:
    return (offset.free_symbols & index_of.keys()) <= coordinates
