"""A 3D body of three point masses held by rods, falling with air drag: position and Z-Y-X
Euler angles, written as a new user would."""
from gencoord import Matrix, Model, cos, sin

model = Model(dim=3)
x = model.coordinate("x", "centre x (m)")
y = model.coordinate("y", "centre y (m)")
z = model.coordinate("z", "centre z (m)", initial=10.0)
yaw = model.coordinate("yaw", "rotation about z (rad)")
pitch = model.coordinate("pitch", "rotation about the new y (rad)", initial=0.2)
roll = model.coordinate("roll", "rotation about the new x (rad)", initial_rate=1.0)
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
drag = model.parameter("drag", 0.05, "drag coefficient (N s/m)")
m = model.parameter("m", 0.5, "mass of each point (kg)")

Rz = Matrix([[cos(yaw), -sin(yaw), 0], [sin(yaw), cos(yaw), 0], [0, 0, 1]])
Ry = Matrix([[cos(pitch), 0, sin(pitch)], [0, 1, 0], [-sin(pitch), 0, cos(pitch)]])
Rx = Matrix([[1, 0, 0], [0, cos(roll), -sin(roll)], [0, sin(roll), cos(roll)]])
R = Rz * Ry * Rx
centre = Matrix([x, y, z])
offsets = {"a": [0.5, 0, 0], "b": [0, 0.4, 0], "c": [0.1, 0.2, 0.3]}
points = {name: model.particle(name, mass=m, position=centre + R * Matrix(offset))
          for name, offset in offsets.items()}
air = model.fixed_point("air", [0, 0, 0])
model.gravity([0, 0, -g])
for point in points.values():
    model.damper(air, point, drag, name=f"drag on {point.name}")
for first, second in (("a", "b"), ("a", "c"), ("b", "c")):
    length = (Matrix(offsets[first]) - Matrix(offsets[second])).norm()
    model.rod(points[first], points[second], length)
