r"""A free 3D rigid body in Z-Y-X Euler angles.

q = (x, y, z, yaw, pitch, roll): the centre of mass and R = Rz(yaw) Ry(pitch) Rx(roll), the
orientation of the body axes, which are its principal axes with moments I_1 < I_2 < I_3.
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
    moments = [model.parameter(f"I_{k}", value, f"principal moment of inertia about body "
                                                f"axis {axis} (kg m^2)")
               for k, (axis, value) in enumerate(zip("xyz", (0.3, 0.45, 0.6)), start=1)]
    model.body("body", mass=m, inertia=Matrix.diag(*moments), frame=Frame(R, centre))
    model.gravity([0, 0, -g])
    return model


model = euler_chart("zyx")
model.add_chart(euler_chart("yzx"))
