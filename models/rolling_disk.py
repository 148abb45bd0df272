r"""A rolling disk: a uniform disk of radius r, thickness h and mass m rolling without slipping
on the ground plane, free to lean, turn and spin.

            | z
            |   ___
            |  /   \   lean phi about the rolling direction
            | |  o  |  spin theta about the axle
            |  \___/
   ---------+----*------------- ground; * the contact point (x, y)

Coordinates: the contact point (x, y), the heading psi (the rolling direction from the x
axis), the lean phi and the spin angle theta. The disk's axes are R = Rz(psi) Rx(phi)
Ry(theta), its axle the body y axis, its centre r above the contact point in its plane. Two
velocity constraints keep the contact point still (model.rolling_wheel); no choice of
coordinates removes them.

Upright straight rolling at spin rate Omega is stable when
    Omega^2 > m g r A / (C (C + m r^2)),
A = m r^2 / 4 + m h^2 / 12 the moment of inertia about a diameter and C = m r^2 / 2 about the
axle (a thin disk: rolling speed r Omega > sqrt(g r / 3)). Linearized about it, the lean
phi, the yaw rate psi' and the lean rate phi' have the eigenvalues 0 and
    +-sqrt((m g r - (C + m r^2) C Omega^2 / A) / (A + m r^2)).
"""
from gencoord import Frame, Matrix, Model, rotation_x, rotation_y, rotation_z

model = Model(dim=3)
x = model.coordinate("x", "contact point, x (m)")
y = model.coordinate("y", "contact point, y (m)")
psi = model.coordinate("psi", "heading: the rolling direction from the x axis (rad)")
phi = model.coordinate("phi", "lean from the vertical, about the rolling direction (rad)",
                       initial=0.05)
theta = model.coordinate("theta", "spin angle about the axle (rad)")
r = model.parameter("r", 0.3, "radius (m)")
h = model.parameter("h", 0.02, "thickness (m)")
m = model.parameter("m", 2.0, "mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")

heading_and_lean = rotation_z(psi) * rotation_x(phi)
centre = Matrix([x, y, 0]) + r * heading_and_lean * Matrix([0, 0, 1])
diameter = m * r**2 / 4 + m * h**2 / 12
disk = model.body("disk", mass=m, inertia=Matrix.diag(diameter, m * r**2 / 2, diameter),
                  frame=Frame(heading_and_lean * rotation_y(theta), centre))
model.gravity([0, 0, -g])
model.rolling_wheel(disk, r, axle=[0, 1, 0], name="rolling")
