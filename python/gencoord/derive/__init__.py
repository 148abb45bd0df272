# SPDX-License-Identifier: BSD-3-Clause
"""The equations of motion, symbolically: the dense contract Mt qddot = Ft + Fi (dense.py)
and its named intermediates (structured.py); the O(n) recursions of trees of particles
(point_tree.py, point_recursion.py) and of rigid bodies (body_tree.py, body_kinematics.py,
body_recursion.py), chosen by recursions.py; the maximal-coordinate penalty model
(maximal.py); Jacobians through shared intermediates (differentiate.py); and the set of
kernels a model gets with their symbolic outputs (kernel_set.py)."""
