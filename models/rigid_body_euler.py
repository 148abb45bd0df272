r"""A free 3D rigid body in Z-Y-X Euler angles.

q = (x, y, z, yaw, pitch, roll): the centre of mass and R = Rz(yaw) Ry(pitch) Rx(roll), the
orientation of the body axes. The body is a uniform box of mass m with sides a > b > c along
its x, y and z axes, its principal axes, so its principal moments m (b^2 + c^2) / 12 <
m (a^2 + c^2) / 12 < m (a^2 + b^2) / 12 grow from x to z.
The parameterization is singular at pitch = +-pi/2 (gimbal lock: yaw and roll turn about the
same axis), that is wherever the body's x axis points along the world's z axis.

A second chart, 'yzx', uses R = Ry(heading) Rz(attitude) Rx(bank), singular at
attitude = +-pi/2, where the body's x axis points along the world's y axis. The two singular
sets are disjoint, so the atlas (gencoord/atlas.hpp) can tumble through either. No gravity
by default, so energy and angular momentum are conserved; spun about the intermediate axis
the body flips over and over (the Dzhanibekov effect).
"""
from generator import Frame, Matrix, Model, rotation_x, rotation_y, rotation_z

# The order of the three elementary rotations in each chart, with the angles' names and
# descriptions, outermost (world) first.
CHARTS = {
    "zyx": [("yaw", "z", "rotation about z (rad)"),
            ("pitch", "y", "rotation about the new y (rad)"),
            ("roll", "x", "rotation about the new x (rad)")],
    "yzx": [("heading", "y", "rotation about y (rad)"),
            ("attitude", "z", "rotation about the new z (rad)"),
            ("bank", "x", "rotation about the new x (rad)")],
}
ROTATIONS = {"x": rotation_x, "y": rotation_y, "z": rotation_z}
# The zyx chart's suggested initial state: a tumble that stays clear of gimbal lock.
INITIAL = {"yaw": (0.0, 0.3), "pitch": (0.2, 1.0), "roll": (0.0, 2.0)}


def euler_chart(chart):
    model = Model(dim=3, chart=chart)
    centre = Matrix([model.coordinate(name, f"centre of mass, {name} (m)") for name in "xyz"])
    R = Matrix.eye(3)
    for name, axis, description in CHARTS[chart]:
        initial, rate = INITIAL.get(name, (0.0, 0.0))
        R = R * ROTATIONS[axis](model.coordinate(name, description, initial=initial,
                                                 initial_rate=rate))
    g = model.parameter("g", 0.0, "gravitational acceleration (m/s^2)")
    m = model.parameter("m", 7.5, "mass (kg)")
    a, b, c = [model.parameter(side, value, f"side of the box along body axis {axis} (m)")
               for side, value, axis in (("a", 0.6, "x"), ("b", 0.45, "y"), ("c", 0.3, "z"))]
    box = Matrix.diag(b**2 + c**2, a**2 + c**2, a**2 + b**2) * m / 12
    model.body("body", mass=m, inertia=box, frame=Frame(R, centre))
    model.gravity([0, 0, -g])
    return model


model = euler_chart("zyx")
model.add_chart(euler_chart("yzx"))
