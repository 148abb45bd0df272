r"""Bead on a hoop rotating about its vertical diameter at a constant rate omega.

            ^ z   omega (rotation about z)
            |
         .--+--.
        /   |   \      theta: the bead's angle from the bottom of the hoop
       |    +    |     radius R
        \   |  o/  <- bead
         '--+--'
            |

x = R (sin(theta) cos(omega t), sin(theta) sin(omega t), -cos(theta)): X depends on time
explicitly. Equilibria: theta = 0, and cos(theta*) = g / (omega^2 R) once omega^2 > g / R
(a pitchfork bifurcation). A damper on theta (relative to the hoop) lets the bead settle.
"""
from gencoord import Model, cos, sin

model = Model(dim=3)
theta = model.coordinate("theta", "angle of the bead from the bottom of the hoop (rad)",
                         initial=0.3)
R = model.parameter("R", 1.0, "hoop radius (m)")
omega = model.parameter("omega", 5.0, "hoop angular velocity about the vertical (rad/s)")
m = model.parameter("m", 1.0, "bead mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
c = model.parameter("c", 0.0, "damping of the bead relative to the hoop (N m s/rad)")

t = model.time
centre = model.fixed_point("centre", [0, 0, 0])
bead = model.particle("bead", mass=m, position=[R * sin(theta) * cos(omega * t),
                                                R * sin(theta) * sin(omega * t),
                                                -R * cos(theta)])
model.gravity([0, 0, -g])
model.generalized_force(theta, -c * model.rate(theta), name="friction on the hoop")
model.rod(centre, bead, R)
model.plane(bead, normal=[-sin(omega * t), cos(omega * t), 0], offset=0)
