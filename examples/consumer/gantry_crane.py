r"""Gantry crane: a trolley on a horizontal rail, held by a buffer spring, carrying a load on a
rope.

    anchor o/\/\/\/\/\/[ trolley ]  --> drive force u (a generalized force on s)
    =================|============   rail (y = 0)
                      \
                       \ l      theta: rope angle from the downward vertical
                        o load

Trolley at (s, 0), tethered to the anchor at the origin by a spring of stiffness k (force per
unit strain) and rest length L; load at (s + l sin(theta), -l cos(theta)). With u = 0 the
system is conservative. The spring's length is |s|, so keep s > 0.
"""
from gencoord import Model, cos, sin

model = Model(dim=2)
s = model.coordinate("s", "trolley position along the rail (m)", initial=1.3)
theta = model.coordinate("theta", "rope angle from the downward vertical (rad)", initial=0.6)
m_trolley = model.parameter("m_trolley", 2.0, "trolley mass (kg)")
m_load = model.parameter("m_load", 1.0, "load mass (kg)")
l = model.parameter("l", 0.8, "rope length (m)")
k = model.parameter("k", 40.0, "buffer spring stiffness, force per unit strain (N)")
L = model.parameter("L", 1.0, "buffer spring rest length (m)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
u = model.parameter("u", 0.0, "drive force on the trolley along the rail (N)")

anchor = model.fixed_point("anchor", [0, 0])
trolley = model.particle("trolley", mass=m_trolley, position=[s, 0])
load = model.particle("load", mass=m_load, position=[s + l * sin(theta), -l * cos(theta)])
model.gravity([0, -g])
model.spring(anchor, trolley, stiffness=k, rest_length=L)
model.generalized_force(s, u, name="drive force")
model.plane(trolley, normal=[0, 1], offset=0)
model.rod(trolley, load, l)
