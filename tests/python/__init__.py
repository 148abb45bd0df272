# SPDX-License-Identifier: BSD-3-Clause
"""The generator's Python tests (stdlib unittest only).

Run from the repository root:
    PYTHONHASHSEED=0 python3 -m unittest discover -s tests/python -t . -v
"""
