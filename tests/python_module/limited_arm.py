r"""Two-link planar arm with an elbow stop: the elbow angle is limited to [-0.5, 0.5] rad, and a
motor torque u, rated at 40 N m, drives the shoulder. Point masses of 1 kg at the ends of two
1 m links; the Python module's joint-limit tests (test_joint_limits_module.py) swing it onto
its stop.
"""
from gencoord import Model, cos, sin

model = Model(dim=2)
a = model.coordinate("shoulder", "shoulder angle from the downward vertical (rad)", initial=1.2)
b = model.coordinate("elbow", "elbow angle from the upper link's direction (rad)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
u = model.input("u", "shoulder motor torque (N m)")

model.particle("elbow_mass", 1.0, [sin(a), -cos(a)])
model.particle("hand", 1.0, [sin(a) + sin(a + b), -cos(a) - cos(a + b)])
model.gravity([0, -g])
model.generalized_force(a, u, name="shoulder motor")
model.limit(b, -0.5, 0.5, name="elbow stop")
model.limit(a, effort=40.0, name="shoulder motor")
