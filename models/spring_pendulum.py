r"""Spring pendulum: the rod is a spring, so the bob moves in the plane (polar coordinates).

      pivot o
            |\
            | \  spring: stiffness k, rest length L, length r
      theta |  \
            |   o bob (m)

x = r (sin(theta), -cos(theta)). The spring is an x-space force (the strain form
f = k (|d| - L) / L) mapped through J^T; an optional air drag -c_air xdot is a user force of
xdot. Polar coordinates are singular at r = 0.
"""
from gencoord import Model, cos, sin

model = Model(dim=2)
r = model.coordinate("r", "distance from the pivot (m)", initial=1.2)
theta = model.coordinate("theta", "angle from the downward vertical (rad)", initial=0.8)
k = model.parameter("k", 200.0, "spring stiffness, force per unit strain (N)")
L = model.parameter("L", 1.0, "spring rest length (m)")
m = model.parameter("m", 1.0, "bob mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
c_air = model.parameter("c_air", 0.0, "air drag coefficient (N s/m)")

pivot = model.fixed_point("pivot", [0, 0])
bob = model.particle("bob", mass=m, position=[r * sin(theta), -r * cos(theta)])
model.gravity([0, -g])
model.spring(pivot, bob, stiffness=k, rest_length=L)
model.force(bob, -c_air * bob.xdot, name="air drag")
