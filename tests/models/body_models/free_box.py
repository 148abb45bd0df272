r"""A free uniform box in Z-Y-X Euler angles, one rigid body.

q = (x, y, z, yaw, pitch, roll): the centre of mass and R = Rz(yaw) Ry(pitch) Rx(roll), the
orientation of the body axes. The box has mass m and sides a > b > c along its x, y and z
axes, its principal axes, so its principal moments m (b^2 + c^2) / 12 < m (a^2 + c^2) / 12 <
m (a^2 + b^2) / 12 grow from x to z. The angles are singular at pitch = +-pi/2, wherever the
body's x axis points along the world's z axis. No gravity by default: energy and angular
momentum are conserved, and spun about its intermediate axis the box turns over and over (the
Dzhanibekov effect).
"""
from gencoord import Frame, Matrix, Model, rpy

model = Model(dim=3)
centre = Matrix([model.coordinate(name, f"centre of mass, {name} (m)") for name in "xyz"])
yaw = model.coordinate("yaw", "rotation about z (rad)")
pitch = model.coordinate("pitch", "rotation about the new y (rad)")
roll = model.coordinate("roll", "rotation about the new x (rad)")
g = model.parameter("g", 0.0, "gravitational acceleration (m/s^2)")
m = model.parameter("m", 7.5, "mass (kg)")
a, b, c = [model.parameter(side, value, f"side of the box along body axis {axis} (m)")
           for side, value, axis in (("a", 0.6, "x"), ("b", 0.45, "y"), ("c", 0.3, "z"))]
box = Matrix.diag(b**2 + c**2, a**2 + c**2, a**2 + b**2) * m / 12
model.body("box", mass=m, inertia=box, frame=Frame(rpy(roll, pitch, yaw), centre))
model.gravity([0, 0, -g])
