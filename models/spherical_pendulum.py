r"""Spherical pendulum: a point mass on a rod free to swing in any direction.

            z
            ^   o pivot (origin)
            |   |\
            |   | \ l
            |   |  \     theta: polar angle from the downward vertical
            |   |   o bob     phi: azimuth about the vertical
            +-----------> x

x = l (sin(theta) cos(phi), sin(theta) sin(phi), -cos(theta)). The parameterization is
singular at theta = 0 and theta = pi (the poles): there J loses rank and phi is undefined.
"""
from generator import Model, cos, sin

model = Model(dim=3)
theta = model.coordinate("theta", "polar angle from the downward vertical (rad)",
                         initial=1.0)
phi = model.coordinate("phi", "azimuth about the vertical axis (rad)", initial_rate=2.0)
l = model.parameter("l", 1.0, "rod length (m)")
m = model.parameter("m", 1.0, "bob mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")

pivot = model.fixed_point("pivot", [0, 0, 0])
bob = model.particle("bob", mass=m, position=[l * sin(theta) * cos(phi),
                                              l * sin(theta) * sin(phi),
                                              -l * cos(theta)])
model.gravity([0, 0, -g])
model.rod(pivot, bob, l)
