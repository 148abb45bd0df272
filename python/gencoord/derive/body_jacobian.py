# SPDX-License-Identifier: BSD-3-Clause
"""J = dX/dv of a joint tree of bodies (body_tree.py) as floats, from its joints.

The sampled checks (the rank of J, the singularity analysis) need J at a few hundred random
configurations. Compiling the symbolic J of a robot takes a second of CPU; this evaluates
each link's frame in its parent's and its joint's subspace S (small expressions), composes
the world frames, and forms each column as rigid-body kinematics does: a coordinate of link
a's joint moves a point x of a or of a descendant with R_a (S_lin + S_ang x R_a^T (x - o_a)),
(R_a, o_a) the world frame of link a.
"""

from __future__ import annotations

from typing import Callable

import sympy as sp

from gencoord.derive.body_tree import BodyTree

Vector = list[float]
Rotation = list[list[float]]


def _rotate(R: Rotation, x: Vector) -> Vector:
    return [R[i][0] * x[0] + R[i][1] * x[1] + R[i][2] * x[2] for i in range(3)]


def _compose(R: Rotation, E: Rotation) -> Rotation:
    return [[sum(R[i][k] * E[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def _cross(a: Vector, b: Vector) -> Vector:
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _local_points(tree: BodyTree, particles: list[str], defaults: dict) -> list[tuple]:
    """(node, the particle's position in the node's link axes) of each particle, in order."""
    where = {}
    for k, node in enumerate(tree.nodes):
        body, inertial = node.link.body, node.link.inertial
        if body is None:
            continue
        assert inertial is not None, node.link.name  # add_link sets both
        for particle, offset in zip(body.particles, body.offsets):
            local = (inertial.rotation * offset + inertial.origin).xreplace(defaults)
            where[particle.name] = (k, [float(value) for value in local])
    return [where[name] for name in particles]


def numeric_body_jacobian(tree: BodyTree, q: list[sp.Symbol], t: sp.Symbol,
                          defaults: dict, particles: list[str]
                          ) -> Callable[[list[float], float], list[list[float]]]:
    """(q, t) -> J of the particles (3 rows each, in `particles` order), parameters at
    `defaults`."""
    nodes = tree.nodes
    nv = sum(len(node.speeds) for node in nodes)  # J's columns: one per speed
    entries = [entry.xreplace(defaults) for node in nodes
               for entry in (*node.rotation, *node.translation, *node.subspace)]
    values = sp.lambdify([q, t], entries, modules="math", cse=True)
    points = _local_points(tree, particles, defaults)
    ancestors: list[list[int]] = []  # each node's, from the root down to itself
    for node in nodes:
        ancestors.append((ancestors[node.parent] if node.parent is not None else [])
                         + [len(ancestors)])

    def evaluate(q_values: list[float], t_value: float) -> list[list[float]]:
        computed = iter([float(value) for value in values(q_values, t_value)])
        world: list[tuple[Rotation, Vector, list[tuple[Vector, Vector]]]] = []
        for node in nodes:
            E = [[next(computed) for _ in range(3)] for _ in range(3)]
            r = [next(computed) for _ in range(3)]
            k = len(node.speeds)
            S = [[next(computed) for _ in range(k)] for _ in range(6)]
            if node.parent is None:
                R, o = E, r
            else:
                R_p, o_p, _ = world[node.parent]
                R, o = _compose(R_p, E), [a + b for a, b in zip(o_p, _rotate(R_p, r))]
            axes = [(_rotate(R, [S[i][c] for i in range(3)]),
                     _rotate(R, [S[i][c] for i in range(3, 6)])) for c in range(k)]
            world.append((R, o, axes))
        rows = []
        for node_index, local in points:
            R, o, _ = world[node_index]
            x = [a + b for a, b in zip(o, _rotate(R, local))]
            block = [[0.0] * nv for _ in range(3)]
            for a in ancestors[node_index]:
                _, o_a, axes = world[a]
                arm = [x_i - o_i for x_i, o_i in zip(x, o_a)]
                for column, (spin, slide) in zip(nodes[a].speeds, axes):
                    moved = _cross(spin, arm)
                    for i in range(3):
                        block[i][column] = slide[i] + moved[i]
            rows.extend(block)
        return rows
    return evaluate
