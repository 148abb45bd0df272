# SPDX-License-Identifier: BSD-3-Clause
"""Property tests (Hypothesis) of the readers of outside input. Run from the repository root
with an interpreter that has Hypothesis:
    PYTHONHASHSEED=0 /usr/bin/python3 -m unittest discover -s tests/properties -t . -v
"""
