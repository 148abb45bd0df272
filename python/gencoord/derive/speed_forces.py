# SPDX-License-Identifier: BSD-3-Clause
"""Forces that act on the speeds directly: the generalized forces a model file puts on its
coordinates (joint springs, damping), and body torques as generalized forces; and G = dq'/dv,
which maps a force per unit rate of q to one per unit speed (speeds.py).
"""

from __future__ import annotations

import sympy as sp

from gencoord.dsl.bodies import torque_generalized_forces
from gencoord.dsl.model import Model


def coordinate_forces(model: Model) -> sp.Matrix:
    """The forces the model file puts on coordinates (generalized forces, joint springs), one
    per speed: a coordinate's speed is its rate."""
    speeds = [speed.symbol for speed in model.speeds]
    forces = sp.zeros(len(speeds), 1)
    for g in model.generalized_forces:
        forces[speeds.index(g.coordinate.rate)] += g.force
    return forces


def rate_matrix(model: Model) -> sp.Matrix:
    """G = dq'/dv of q' = G(q) v (nq x nv)."""
    return sp.Matrix(model.coordinate_rates()).jacobian([s.symbol for s in model.speeds])


def generalized_force_vector(model: Model, q: list[sp.Symbol]) -> sp.Matrix:
    """Q: the forces acting directly on v (generalized forces, joint springs, body torques);
    a body torque's virtual work Q_q . dq per unit speed is G^T Q_q."""
    torques = torque_generalized_forces(model, q)
    if model.has_generalized_speeds:
        torques = rate_matrix(model).T * torques
    return torques + coordinate_forces(model)
