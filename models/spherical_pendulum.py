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

An atlas of two charts keeps the simulation going through the poles: chart 'pole_down'
(above) and chart 'pole_x', spherical coordinates about the x axis,
x = l (cos(alpha), sin(alpha) cos(beta), sin(alpha) sin(beta)), singular only where the bob
is on the x axis. No configuration is singular in both, so gencoord/atlas/atlas.hpp can always
move to a well-conditioned chart.
"""
from gencoord import Model, cos, sin


def spherical_chart(chart):
    """The pendulum in spherical coordinates whose poles are on the z (pole_down) or x axis."""
    model = Model(dim=3, chart=chart)
    if chart == "pole_down":
        theta = model.coordinate("theta", "polar angle from the downward vertical (rad)",
                                 initial=1.0)
        phi = model.coordinate("phi", "azimuth about the vertical axis (rad)",
                               initial_rate=2.0)
    else:
        # the suggested state is the bob hanging at rest (the first guess of the inverse map)
        theta = model.coordinate("alpha", "polar angle from the +x axis (rad)",
                                 initial=1.5707963267948966)
        phi = model.coordinate("beta", "azimuth about the x axis, from +y (rad)",
                               initial=-1.5707963267948966)
    l = model.parameter("l", 1.0, "rod length (m)")
    m = model.parameter("m", 1.0, "bob mass (kg)")
    g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
    pivot = model.fixed_point("pivot", [0, 0, 0])
    if chart == "pole_down":
        position = [l * sin(theta) * cos(phi), l * sin(theta) * sin(phi), -l * cos(theta)]
    else:
        position = [l * cos(theta), l * sin(theta) * cos(phi), l * sin(theta) * sin(phi)]
    bob = model.particle("bob", mass=m, position=position)
    model.gravity([0, 0, -g])
    model.rod(pivot, bob, l)
    return model


model = spherical_chart("pole_down")
model.add_chart(spherical_chart("pole_x"))
