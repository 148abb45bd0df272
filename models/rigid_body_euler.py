r"""A free 3D rigid body in Z-Y-X Euler angles: one body, whose centre of mass is off its
reference point and whose inertia tensor is not diagonal in its axes.

              z ^
                |   * centre of mass, at c in body axes
                |  /
                | /          body axes x, y, z at the reference point o; the principal
                |/           axes of the inertia tensor are none of them
                o-------> y
               /
              x

q = (x, y, z, yaw, pitch, roll): the reference point and R = Rz(yaw) Ry(pitch) Rx(roll). The
centre of mass sits at o + R c, so q's translation and rotation are coupled in Mt. The body
is a uniform box of sides a, b, c whose edges are turned against the body axes (by fixed
roll, pitch and yaw angles), so its inertia tensor in body axes is full; any positive sides
make a real body. The defaults give nearly the mass distribution of four point masses (1, 2,
3, 1.5 kg at (0.5, 0, 0), (0, 0.4, 0), (0, 0, 0.3), (0.2, 0.3, 0.25)). The parameterization
is singular at pitch = +-pi/2 (gimbal lock: yaw and roll turn about the same axis), wherever
the body's x axis points along the world's z axis.

A second chart, 'yzx', uses R = Ry(heading) Rz(attitude) Rx(bank), singular at
attitude = +-pi/2, where the body's x axis points along the world's y axis. The two singular
sets are disjoint, so the atlas (gencoord/atlas/atlas.hpp) can tumble through either. No gravity
by default, so energy and angular momentum are conserved.
"""
from gencoord import EULER_CHARTS, Frame, Matrix, Model, rotation_about, rpy

# The zyx chart's suggested initial state: a tumble that stays clear of gimbal lock.
INITIAL = {"yaw": (0.0, 0.3), "pitch": (0.2, 1.0), "roll": (0.0, 2.0)}
CENTRE = {"com_x": 0.1067, "com_y": 0.1667, "com_z": 0.17}
SIDES = {"a": 0.703, "b": 0.641, "c": 0.29}
BOX_AXES = rpy(2.684, -0.526, -1.479)  # the box's edges (its principal axes) in body axes


def euler_chart(chart):
    model = Model(dim=3, chart=chart)
    origin = Matrix([model.coordinate(name, f"reference point, {name} (m)") for name in "xyz"])
    R = Matrix.eye(3)
    for name, axis, description in EULER_CHARTS[chart]:
        initial, rate = INITIAL.get(name, (0.0, 0.0))
        angle = model.coordinate(name, description, initial=initial, initial_rate=rate)
        R = R * rotation_about(axis, angle)
    g = model.parameter("g", 0.0, "gravitational acceleration (m/s^2)")
    m = model.parameter("m", 7.5, "mass of the body (kg)")
    centre = Matrix([model.parameter(name, value, f"centre of mass, body axis {name[-1]} (m)")
                     for name, value in CENTRE.items()])
    a, b, c = [model.parameter(name, value, f"side {name} of the box (m)")
               for name, value in SIDES.items()]
    principal = Matrix.diag(b**2 + c**2, a**2 + c**2, a**2 + b**2) * m / 12
    model.body("body", mass=m, inertia=BOX_AXES * principal * BOX_AXES.T,
               frame=Frame(R, origin + R * centre))
    model.gravity([0, 0, -g])
    return model


model = euler_chart("zyx")
model.add_chart(euler_chart("yzx"))
