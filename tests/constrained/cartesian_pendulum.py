r"""The planar pendulum in Cartesian coordinates: the bob at (x, y), kept at distance l from
the pivot by the holonomic constraint x^2 + y^2 - l^2 = 0. Its motion is models/pendulum.py's
with x = l sin(theta), y = -l cos(theta); the multiplier of the constraint is
lambda = -T / (2 l), T = m (l theta'^2 + g cos(theta)) the rod's tension.
"""
from gencoord import Model

model = Model(dim=2)
x = model.coordinate("x", "horizontal position of the bob (m)", initial=0.479425538604203)
y = model.coordinate("y", "vertical position of the bob (m)", initial=-0.8775825618903728)
l = model.parameter("l", 1.0, "rod length (m)")
m = model.parameter("m", 1.0, "bob mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")

model.particle("bob", mass=m, position=[x, y])
model.gravity([0, -g])
model.holonomic_constraint(x**2 + y**2 - l**2, name="rod")
