# SPDX-License-Identifier: BSD-3-Clause
"""Writes a URDF with every inertia tensor's products of inertia set to zero and the robot
renamed: MuJoCo keeps a general tensor as principal moments and a rotation (to about 1e-7),
a diagonal one exactly, so on such a file the generated model and MuJoCo must agree to
round-off.

Usage: diagonal_inertia.py IN.urdf OUT.urdf NAME
"""
import re
import sys


def main() -> None:
    source, target, name = sys.argv[1:]
    with open(source, encoding="utf-8") as file:
        text = file.read()
    text = re.sub(r'\b(ixy|ixz|iyz)="[^"]*"', r'\1="0"', text)
    text = re.sub(r'<robot name="[^"]*"', f'<robot name="{name}"', text, count=1)
    with open(target, "w", encoding="utf-8") as file:
        file.write(text)


if __name__ == "__main__":
    main()
