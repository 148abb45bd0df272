r"""Two rigid bodies in 3D joined by hinges, each with a full (non-diagonal) inertia tensor.

Body 1 turns by q1 about the fixed axis (4, 0, 3)/5 through the origin; body 2 turns by q2
about the axis (0, 3, 4)/5 of body 1's axes, through the point j of body 1. c1 is body 1's
centre of mass in its axes (from the origin), c2 body 2's in its axes (from the hinge), and
I1, I2 the inertia tensors about the centres of mass in body axes. Gravity pulls along -z.
"""
from gencoord import Frame, Matrix, Model, axis_angle

model = Model(dim=3)
q1 = model.coordinate("q1", "angle of body 1 about the fixed hinge (rad)", initial=0.4)
q2 = model.coordinate("q2", "angle of body 2 about the hinge on body 1 (rad)", initial=-0.7)
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")


def vector(name, values, description):
    return Matrix([model.parameter(f"{name}{axis}", value, f"{description}, {axis} (m)")
                   for axis, value in zip("xyz", values)])


def tensor(name, values):
    """A symmetric tensor from the parameters name_xx, name_yy, name_zz, name_xy, name_xz,
    name_yz (kg m^2)."""
    entries = {key: model.parameter(f"{name}_{key}", value, f"inertia {name}, {key} (kg m^2)")
               for key, value in zip(("xx", "yy", "zz", "xy", "xz", "yz"), values)}
    return Matrix([[entries["xx"], entries["xy"], entries["xz"]],
                   [entries["xy"], entries["yy"], entries["yz"]],
                   [entries["xz"], entries["yz"], entries["zz"]]])


m1 = model.parameter("m1", 1.5, "mass of body 1 (kg)")
m2 = model.parameter("m2", 0.8, "mass of body 2 (kg)")
c1 = vector("c1", (0.1, -0.05, -0.3), "centre of mass of body 1")
j = vector("j", (0.05, 0.02, -0.6), "hinge of body 2 on body 1")
c2 = vector("c2", (-0.04, 0.08, -0.25), "centre of mass of body 2 from its hinge")
I1 = tensor("I1", (0.05, 0.04, 0.03, 0.004, -0.003, 0.002))
I2 = tensor("I2", (0.02, 0.025, 0.015, -0.002, 0.001, 0.003))

R1 = axis_angle([4, 0, 3], q1)
R2 = R1 * axis_angle([0, 3, 4], q2)
hinge = R1 * j
body1 = model.body("body1", mass=m1, inertia=I1, frame=Frame(R1, R1 * c1))
body2 = model.body("body2", mass=m2, inertia=I2, frame=Frame(R2, hinge + R2 * c2))
model.gravity([0, 0, -g])

# the hinges, for the maximal-coordinate model: two points on each axis
model.pin(body1.point(-c1, name="body1_pivot"), [0, 0, 0], name="pivot")
model.pin(body1.point(Matrix([4, 0, 3]) / 5 - c1, name="body1_axle"), Matrix([4, 0, 3]) / 5,
          name="axle")
model.pin(body2.point(-c2, name="body2_hinge"), body1.point(j - c1, name="body1_hinge"),
          name="hinge")
model.pin(body2.point(Matrix([0, 3, 4]) / 5 - c2, name="body2_hinge_axle"),
          body1.point(j + Matrix([0, 3, 4]) / 5 - c1, name="body1_hinge_axle"),
          name="hinge_axle")
