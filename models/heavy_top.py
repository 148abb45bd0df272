r"""A heavy symmetric top spinning with its tip on a fixed point.

q = (phi, theta, psi), Z-X-Z Euler angles: precession phi about the vertical, nutation theta
(the tilt of the symmetry axis from the vertical) and spin psi about the symmetry axis, so the
body axes are R = Rz(phi) Rx(theta) Rz(psi). The centre of mass is a distance d along the
symmetry axis from the tip. The top's disc is a uniform cylinder of radius r and thickness h
(a massless spindle joins it to the tip), so the moment of inertia about the symmetry axis is
C = m r^2 / 2 and about the transverse axes through the centre of mass A = m (3 r^2 + h^2) / 12.

A fast top (C psi_dot large) precesses steadily at about m g d / (C psi_dot). The angles are
singular at theta = 0, the upright top, where phi and psi turn about the same axis.
"""
from gencoord import Frame, Matrix, Model, rotation_x, rotation_z

model = Model(dim=3)
phi = model.coordinate("phi", "precession about the vertical (rad)")
theta = model.coordinate("theta", "tilt of the symmetry axis from the vertical (rad)",
                         initial=0.5)
psi = model.coordinate("psi", "spin about the symmetry axis (rad)", initial_rate=150.0)
m = model.parameter("m", 0.5, "mass (kg)")
d = model.parameter("d", 0.05, "distance from the tip to the centre of mass (m)")
r = model.parameter("r", 0.05, "radius of the disc (m)")
h = model.parameter("h", 0.02, "thickness of the disc (m)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")

# any positive r and h give a possible body (A and C as parameters could break the triangle
# inequality C < 2 A)
A = m * (3 * r**2 + h**2) / 12
C = m * r**2 / 2

R = rotation_z(phi) * rotation_x(theta) * rotation_z(psi)
top = model.body("top", mass=m, inertia=Matrix.diag(A, A, C),
                 frame=Frame(R, R * Matrix([0, 0, d])))
model.pin(top.point([0, 0, -d], name="tip"), [0, 0, 0], name="tip")
model.gravity([0, 0, -g])
