r"""A coin (a disk of radius r, thickness h, mass m) upright on the ground plane, rolling without
slipping: the centre at (x, y, r), heading psi, spin angle phi. The contact point does not
slide: x' = r cos(psi) phi', y' = r sin(psi) phi', two velocity constraints no choice of
coordinates removes. Energy is conserved; the spin rate and the turning rate are constant;
the centre moves on a circle of radius r phi' / psi'.
"""
from gencoord import Frame, Matrix, Model, cos, rotation_z, sin

model = Model(dim=3)
x = model.coordinate("x", "centre, x (m)")
y = model.coordinate("y", "centre, y (m)")
psi = model.coordinate("psi", "heading: the rolling direction from the x axis (rad)")
phi = model.coordinate("phi", "spin angle (rad)")
r = model.parameter("r", 0.1, "radius (m)")
h = model.parameter("h", 0.01, "thickness (m)")
m = model.parameter("m", 0.5, "mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")

# body axes: z along the axle (horizontal), the disk in its x-y plane
axes = rotation_z(psi) * Matrix([[1, 0, 0], [0, 0, 1], [0, -1, 0]]) * rotation_z(phi)
model.body("coin", mass=m, inertia=Matrix.diag(*[m * r**2 / 4 + m * h**2 / 12] * 2, m * r**2 / 2),
           frame=Frame(axes, [x, y, r]))
model.gravity([0, 0, -g])
model.velocity_constraint([model.rate(x) - r * cos(psi) * model.rate(phi),
                           model.rate(y) - r * sin(psi) * model.rate(phi)], name="rolling")
