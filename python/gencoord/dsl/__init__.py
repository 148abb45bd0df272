# SPDX-License-Identifier: BSD-3-Clause
"""The model-file API: `Model` and its declarations (model.py, items.py), rigid-body poses
(frames.py), bodies as point masses (bodies.py) and joint trees of links (joints.py). Nothing
here derives anything."""
