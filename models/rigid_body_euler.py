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
about the same axis). No gravity by default, so energy and angular momentum are conserved.
"""
from generator import Matrix, Model, cos, sin

model = Model(dim=3)
x = model.coordinate("x", "body origin, x (m)")
y = model.coordinate("y", "body origin, y (m)")
z = model.coordinate("z", "body origin, z (m)")
yaw = model.coordinate("yaw", "rotation about z (rad)", initial_rate=0.3)
pitch = model.coordinate("pitch", "rotation about the new y (rad)", initial=0.2,
                         initial_rate=1.0)
roll = model.coordinate("roll", "rotation about the new x (rad)", initial_rate=2.0)
g = model.parameter("g", 0.0, "gravitational acceleration (m/s^2)")
masses = [model.parameter(f"m_{name}", value, f"mass of point {name} (kg)")
          for name, value in (("a", 1.0), ("b", 2.0), ("c", 3.0), ("d", 1.5))]

Rz = Matrix([[cos(yaw), -sin(yaw), 0], [sin(yaw), cos(yaw), 0], [0, 0, 1]])
Ry = Matrix([[cos(pitch), 0, sin(pitch)], [0, 1, 0], [-sin(pitch), 0, cos(pitch)]])
Rx = Matrix([[1, 0, 0], [0, cos(roll), -sin(roll)], [0, sin(roll), cos(roll)]])
R = Rz * Ry * Rx
origin = Matrix([x, y, z])
body_points = {"a": [0.5, 0, 0], "b": [0, 0.4, 0], "c": [0, 0, 0.3], "d": [0.2, 0.3, 0.25]}
points = {}
for (name, offset), mass in zip(body_points.items(), masses):
    points[name] = model.particle(name, mass=mass, position=origin + R * Matrix(offset))
model.gravity([0, 0, -g])
for first, second in (("a", "b"), ("a", "c"), ("a", "d"), ("b", "c"), ("b", "d"), ("c", "d")):
    offset = Matrix(body_points[first]) - Matrix(body_points[second])
    model.rod(points[first], points[second], offset.norm())
