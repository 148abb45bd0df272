r"""A free 3D rigid body built from four point masses, in Z-Y-X Euler angles.

              z ^    d (m_d)
                |   /|
                |  / |        body frame: a, b, c on the axes, d off them, so the
                | /  |        inertia tensor has three different principal moments
         c (m_c)o----o b (m_b)
               /
              o a (m_a)

q = (x, y, z, yaw, pitch, roll): the centre of the body frame and R = Rz(yaw) Ry(pitch)
Rx(roll). The parameterization is singular at pitch = +-pi/2 (gimbal lock: yaw and roll turn
about the same axis), that is wherever the body's x axis points along the world's z axis.

A second chart, 'yzx', uses R = Ry(heading) Rz(attitude) Rx(bank), singular at
attitude = +-pi/2, where the body's x axis points along the world's y axis. The two singular
sets are disjoint, so the atlas (gencoord/atlas.hpp) can tumble through either. No gravity
by default, so energy and angular momentum are conserved.
"""
from generator import EULER_CHARTS, Matrix, Model, rotation_about

# The zyx chart's suggested initial state: a tumble that stays clear of gimbal lock.
INITIAL = {"yaw": (0.0, 0.3), "pitch": (0.2, 1.0), "roll": (0.0, 2.0)}
BODY_POINTS = {"a": [0.5, 0, 0], "b": [0, 0.4, 0], "c": [0, 0, 0.3], "d": [0.2, 0.3, 0.25]}


def euler_chart(chart):
    model = Model(dim=3, chart=chart)
    origin = Matrix([model.coordinate(name, f"body origin, {name} (m)") for name in "xyz"])
    R = Matrix.eye(3)
    for name, axis, description in EULER_CHARTS[chart]:
        initial, rate = INITIAL.get(name, (0.0, 0.0))
        angle = model.coordinate(name, description, initial=initial, initial_rate=rate)
        R = R * rotation_about(axis, angle)
    g = model.parameter("g", 0.0, "gravitational acceleration (m/s^2)")
    masses = [model.parameter(f"m_{name}", value, f"mass of point {name} (kg)")
              for name, value in (("a", 1.0), ("b", 2.0), ("c", 3.0), ("d", 1.5))]
    points = {}
    for (name, offset), mass in zip(BODY_POINTS.items(), masses):
        points[name] = model.particle(name, mass=mass, position=origin + R * Matrix(offset))
    model.gravity([0, 0, -g])
    for first, second in (("a", "b"), ("a", "c"), ("a", "d"), ("b", "c"), ("b", "d"),
                          ("c", "d")):
        offset = Matrix(BODY_POINTS[first]) - Matrix(BODY_POINTS[second])
        model.rod(points[first], points[second], offset.norm())
    return model


model = euler_chart("zyx")
model.add_chart(euler_chart("yzx"))
