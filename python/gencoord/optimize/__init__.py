# SPDX-License-Identifier: BSD-3-Clause
"""One common-subexpression elimination over every output of a model, then per-kernel
straight-line programs (optimizer.py, with the state its steps hand on in state.py), cut into
parts (split.py) and counted (opcount.py)."""
