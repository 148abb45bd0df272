# SPDX-License-Identifier: BSD-3-Clause
"""The O(n) recursions for a model that is a tree: of particles (point_tree.py,
derive/point_recursion.py) or of rigid bodies joined by joints (body_tree.py, body_recursion.py)."""

from __future__ import annotations

from gencoord.derive.body_recursion import body_recursive_dynamics
from gencoord.derive.body_tree import body_tree
from gencoord.derive.dense import Kinematics
from gencoord.dsl.model import Model
from gencoord.derive.point_recursion import RecursiveDynamics, recursive_dynamics


def tree_dynamics(model: Model, kin: Kinematics, derivation: bool = True,
                  square_outputs: bool = True) -> RecursiveDynamics | None:
    """qddot and the inverse-dynamics residual by the recursions, with `derivation` every
    other output too (Mt and J only with `square_outputs`), or None for a model that is no
    tree (it keeps the dense kernels)."""
    points = kin.tree
    if points is not None:
        return recursive_dynamics(model, kin, points, derivation, square_outputs)
    bodies = body_tree(model)
    if bodies is not None:
        return body_recursive_dynamics(model, kin, bodies, derivation, square_outputs)
    return None
