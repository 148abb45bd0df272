r"""Delta robot: three motors on a fixed base each swing an upper arm; a parallelogram of two
rods joins each elbow to a moving platform, which the three closed loops keep parallel to the
base, so the platform only translates (Clavel's parallel robot, used for pick-and-place).

      base (radius R), motor i at angle alpha_i = 120 i degrees about the vertical
        B_i o----------o J_i      upper arm: length l_a, swung down by theta_i
                        \
                         \        lower arm: a parallelogram of rods, length l_b
                          \
                 P  o------o E_i  platform (radius r), at P = (x, y, z)

Coordinates: the three upper-arm angles theta_i (down from the base's plane, about the axis
tangent to the base circle at B_i) and the platform's position. Each lower arm keeps its two
ends l_b apart: three holonomic constraints |E_i - J_i| = l_b, written as
(|E_i - J_i|^2 - l_b^2) / (2 l_b) so that the multiplier is the arm's force along its
length in newtons (positive: the arm pushes the platform away from the elbow; a hanging
platform keeps its arms in tension, negative). Three degrees of freedom
are left: the platform's position.

The upper arms are uniform solid rods (mass m_a, radius rho); each lower arm is modelled as
two point masses, half its mass m_b at the elbow and half at the platform, the usual model of
a parallelogram of light rods. The motors apply the torques u_1, u_2, u_3.
"""
import math

from gencoord import Frame, Matrix, Model, rotation_y, rotation_z

R_BASE, R_PLATFORM, UPPER, LOWER, THETA0 = 0.2, 0.05, 0.35, 0.8, 0.5
# the platform's height below the base when every upper arm is at THETA0
Z0 = -UPPER * math.sin(THETA0) - math.sqrt(
    LOWER**2 - (R_PLATFORM - R_BASE - UPPER * math.cos(THETA0))**2)

model = Model(dim=3)
thetas = [model.coordinate(f"theta_{i}", f"upper arm {i} below the base's plane (rad)",
                           initial=THETA0) for i in (1, 2, 3)]
x = model.coordinate("x", "platform centre, x (m)")
y = model.coordinate("y", "platform centre, y (m)")
z = model.coordinate("z", "platform centre, z (m)", initial=Z0)
base = model.parameter("R", R_BASE, "base radius: motor axis to centre (m)")
platform_radius = model.parameter("r", R_PLATFORM, "platform radius: joint to centre (m)")
l_a = model.parameter("l_a", UPPER, "upper arm length (m)")
l_b = model.parameter("l_b", LOWER, "lower arm (parallelogram) length (m)")
m_a = model.parameter("m_a", 0.4, "upper arm mass (kg)")
rho = model.parameter("rho", 0.015, "upper arm radius (m)")
m_b = model.parameter("m_b", 0.15, "lower arm mass, both rods (kg)")
m_p = model.parameter("m_p", 0.5, "platform and payload mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")

centre = Matrix([x, y, z])
platform_mass = m_p + 3 * m_b / 2
platform = model.particle("platform", mass=platform_mass, position=centre)
for i, theta in enumerate(thetas, start=1):
    alpha = 2 * math.pi * (i - 1) / 3
    radial = Matrix([math.cos(alpha), math.sin(alpha), 0])
    arm_axes = rotation_z(alpha) * rotation_y(theta)  # x along the arm, y its motor's axis
    along = arm_axes * Matrix([1, 0, 0])
    arm = model.body(f"upper_arm_{i}", mass=m_a,
                     inertia=Matrix.diag(m_a * rho**2 / 2,
                                         *[m_a * (3 * rho**2 + l_a**2) / 12] * 2),
                     frame=Frame(arm_axes, base * radial + l_a / 2 * along))
    elbow = model.particle(f"elbow_{i}", mass=m_b / 2, position=base * radial + l_a * along)
    span = platform.x + platform_radius * radial - elbow.x
    model.holonomic_constraint((span.dot(span) - l_b**2) / (2 * l_b), name=f"lower_arm_{i}")
    # the motor's hinge (two points of its axis) and the elbow, which the coordinates
    # already keep, restated for the maximal-coordinate model (gencoord crosscheck)
    motor_axis = rotation_z(alpha) * Matrix([0, 1, 0])
    model.pin(arm.point([-l_a / 2, 0, 0], name=f"motor_{i}_near"), base * radial,
              name=f"motor_{i}_near")
    model.pin(arm.point([-l_a / 2, l_a / 2, 0], name=f"motor_{i}_far"),
              base * radial + l_a / 2 * motor_axis, name=f"motor_{i}_far")
    model.pin(elbow, arm.point([l_a / 2, 0, 0], name=f"elbow_{i}_joint"), name=f"elbow_{i}")
    model.generalized_force(theta, model.input(f"u_{i}", f"motor torque on arm {i} (N m)"),
                            name=f"motor_{i}")
model.gravity([0, 0, -g])
