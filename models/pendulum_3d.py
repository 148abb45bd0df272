r"""3D pendulum: pivot and bob are both particles in 3D.

        y
        ^      pivot (pinned at the origin)
        |     o
        |    /|
        |   / | theta
        |  /  |
        | o   v -y
        | bob, swings in the z = 0 plane
        +-------------> x

6 maximal coordinates (two 3D particles), 5 constraints (pivot pinned: 3; rod: 1; bob in
the plane z = 0: 1), so 1 generalized coordinate: the angle theta. The pivot's X does not
depend on theta, so it adds nothing to Mt; its mass matters only in the maximal model.
"""
from gencoord import Model, cos, sin

model = Model(dim=3)
theta = model.coordinate("theta", "angle of the rod from the downward vertical (rad)",
                         initial=0.5)
l = model.parameter("l", 1.0, "rod length (m)")
m = model.parameter("m", 1.0, "bob mass (kg)")
m_pivot = model.parameter("m_pivot", 1.0, "pivot mass, used by the maximal model (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")

origin = model.fixed_point("origin", [0, 0, 0])
pivot = model.particle("pivot", mass=m_pivot, position=[0, 0, 0])
bob = model.particle("bob", mass=m, position=[l * sin(theta), -l * cos(theta), 0])
model.gravity([0, -g, 0])
model.pin(pivot, origin)
model.rod(pivot, bob, l)
model.plane(bob, normal=[0, 0, 1], offset=0)
