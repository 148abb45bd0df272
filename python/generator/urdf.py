# SPDX-License-Identifier: BSD-3-Clause
"""`generator.urdf`, the former name of `gencoord.urdf`."""

from generator import tell_to_rename

tell_to_rename("generator.urdf", "gencoord.urdf")

from gencoord.urdf import load_urdf  # noqa: E402,F401
