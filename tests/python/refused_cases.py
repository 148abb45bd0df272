"""Model files the generator must refuse, each with the key words its error must contain.

A case is (model source, key words); `# <- error` marks the line the message must name (a
case without a mark must name the file). Sources are dedented and start from PREAMBLE
unless they import the generator themselves.
"""

from __future__ import annotations

MARK = "# <- error"

PREAMBLE = """\
import sympy
from generator import Model, cos, sin, sqrt, tan
model = Model(dim=2)
theta = model.coordinate("theta", "angle from the downward vertical (rad)")
"""
BOB = 'bob = model.particle("bob", mass=1, position=[sin(theta), -cos(theta)])\n'


def _position(x: str, before: str = "") -> str:
    """A model whose bob's x-coordinate is `x` (the marked line)."""
    return (PREAMBLE + before + f'bob = model.particle("bob", mass=1, position=[{x}, '
            f"-cos(theta)])  {MARK}\n")


def _parameter(name: str, default: str = "1.0") -> str:
    """A model with one parameter `name` (the marked line) scaling the bob's position."""
    return (PREAMBLE + f'k = model.parameter("{name}", {default}, "a length (m)")  {MARK}\n'
            'bob = model.particle("bob", mass=1, position=[k * sin(theta), -k * cos(theta)])\n')


# --- the model file ends early or cannot be read --------------------------------------------
EXITS = {
    "sys_exit_0": (PREAMBLE + BOB + f"import sys\nsys.exit(0)  {MARK}\n", ["exited"]),
    "raise_system_exit": (PREAMBLE + BOB + f"raise SystemExit  {MARK}\n", ["exited"]),
    "exit_with_message": (PREAMBLE + BOB + f'raise SystemExit("done")  {MARK}\n',
                          ["exited", "done"]),
}
