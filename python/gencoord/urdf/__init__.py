# SPDX-License-Identifier: BSD-3-Clause
"""URDF robot descriptions: read with line numbers (xml_lines.py), checked as a tree of links
and joints (description.py) and added to a model as a joint tree (load.py)."""

from gencoord.urdf.load import load_urdf  # noqa: F401
