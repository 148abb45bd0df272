r"""Bead on a parabola (test model): no declared constraint can express the wire, so the
maximal model keeps the bead on it with the runtime's manifold spring (a zero-length spring
kappa to the closest point X(q*(x))).

      y
      |  .            .
      |   .          .     y = a s^2
      |     .  o   .       bead at (s, a s^2)
      +-------'--'-----> x

nq = 1 < nx = 2, no declared constraints.
"""
from gencoord import Model

model = Model(dim=2)
s = model.coordinate("s", "horizontal position of the bead (m)", initial=0.8)
a = model.parameter("a", 0.5, "curvature of the parabola (1/m)")
m = model.parameter("m", 1.0, "bead mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")

bead = model.particle("bead", mass=m, position=[s, a * s**2])
model.gravity([0, -g])
