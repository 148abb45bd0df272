r"""The Furuta (rotary inverted) pendulum: a horizontal arm turned by a motor about the vertical,
and a pendulum swinging about the arm's axis at its tip.

        z ^
          |      arm (m_a, length L_a), turns by phi about z
          o==========o
                     |  pendulum (m_p, length L_p), turns by theta about the arm
                     |

phi is the arm's angle about the vertical and theta the pendulum's angle from the downward
vertical about the arm's axis. Both links are uniform bars of square section (side w), so
each inertia tensor is diagonal in the bar's axes. The motor's torque tau acts on the arm.
"""
from gencoord import Frame, Matrix, Model, rotation_x, rotation_z

model = Model(dim=3)
phi = model.coordinate("phi", "arm angle about the vertical (rad)", initial_rate=1.0)
theta = model.coordinate("theta", "pendulum angle from the downward vertical (rad)",
                         initial=2.5)
m_a = model.parameter("m_a", 0.3, "mass of the arm (kg)")
L_a = model.parameter("L_a", 0.2, "length of the arm (m)")
m_p = model.parameter("m_p", 0.1, "mass of the pendulum (kg)")
L_p = model.parameter("L_p", 0.3, "length of the pendulum (m)")
w = model.parameter("w", 0.01, "side of the bars' square section (m)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
tau = model.parameter("tau", 0.0, "motor torque on the arm (N m)")


def bar(mass, length, axis):
    """The inertia tensor of a uniform bar of square section along body axis `axis`."""
    along, across = mass * w**2 / 6, mass * (length**2 + w**2) / 12
    return Matrix.diag(*[along if k == axis else across for k in range(3)])


# the arm lies along its body x axis; the pendulum hangs along its body -z axis
R_arm = rotation_z(phi)
arm = model.body("arm", mass=m_a, inertia=bar(m_a, L_a, 0),
                 frame=Frame(R_arm, R_arm * Matrix([L_a / 2, 0, 0])))
R_pendulum = R_arm * rotation_x(theta)
tip = R_arm * Matrix([L_a, 0, 0])
pendulum = model.body("pendulum", mass=m_p, inertia=bar(m_p, L_p, 2),
                      frame=Frame(R_pendulum, tip + R_pendulum * Matrix([0, 0, -L_p / 2])))
model.torque(arm, [0, 0, tau], name="motor")
model.gravity([0, 0, -g])

# the joints, for the maximal-coordinate model: two points on each rotation axis
model.pin(arm.point([-L_a / 2, 0, 0], name="arm_hub"), [0, 0, 0], name="hub")
model.pin(arm.point([-L_a / 2, 0, L_a / 2], name="arm_shaft"), [0, 0, L_a / 2], name="shaft")
model.pin(pendulum.point([0, 0, L_p / 2], name="pendulum_pivot"),
          arm.point([L_a / 2, 0, 0], name="arm_tip"), name="pivot")
model.pin(pendulum.point([L_a / 2, 0, L_p / 2], name="pendulum_axle"),
          arm.point([L_a, 0, 0], name="arm_axle"), name="axle")
