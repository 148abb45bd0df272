# SPDX-License-Identifier: BSD-3-Clause
"""The checks of a loaded model, before and beside its derivation: declarations (validate.py),
the rank of J = dX/dq (full_rank.py, redundancy.py, singularities.py, conditioning.py),
declared constraints (constraints.py), atlas charts (atlas.py) and conservative forces
(conservative.py), each within a CPU budget (budget.py)."""
