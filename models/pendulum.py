r"""Planar pendulum: a point mass on a massless rigid rod.

      pivot o-----> x
            |\
            | \  l
      theta |-'\
            |   o bob (m)
            v y

The same example in 2D: 2 maximal coordinates, 1 constraint (the rod), 1 generalized
coordinate. Mt = m l^2, forces = -m g l sin(theta).
"""
from gencoord import Model, cos, sin

model = Model(dim=2)
theta = model.coordinate("theta", "angle from the downward vertical (rad)", initial=0.5)
l = model.parameter("l", 1.0, "rod length (m)")
m = model.parameter("m", 1.0, "bob mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")

pivot = model.fixed_point("pivot", [0, 0])
bob = model.particle("bob", mass=m, position=[l * sin(theta), -l * cos(theta)])
model.gravity([0, -g])
model.rod(pivot, bob, l)
