r"""The Whipple bicycle with the benchmark parameters of Meijaard, Papadopoulos, Ruina and
Schwab (2007): four rigid bodies (the rear wheel R, the rear frame with the rider B, the
front frame with fork and handlebar H, the front wheel F), knife-edge wheels rolling without
slipping on the ground, a steer axis tilted back by lam, the trail c.

             __ H
    B  o    /
      /|   / steer axis (lam from vertical)
     / |  /
   (  R  )     (  F  )
  ----*-----------*--- c ---+------ ground
      rear contact  front contact, the steer axis meets the ground c ahead of it

The paper's axes are x forward, y to the right, z down, with the rear contact at the origin
in the upright reference configuration; its parameters (w, c, lam, the wheels' radii, masses
and inertias, the rear and front frames' centres of mass and inertia tensors) are given in
those axes. This file builds the bicycle in them and turns the result by pi about x into the
model's axes (z up), so every coordinate keeps the paper's meaning: the rear contact point
(x, y), yaw psi, roll phi and pitch theta of the rear frame (Z-X-Y about the paper's axes),
the rear wheel's angle theta_r, the steer angle delta and the front wheel's angle theta_f.

Constraints: both wheels roll without slipping (two velocity constraints each), and the front
wheel touches the ground (a holonomic constraint, which sets the pitch); the rear wheel
touches it by construction. Eight coordinates, eight speeds, five constraints: three degrees
of freedom (roll, steer and the rear wheel's rotation) and the configuration's seven.

Linearized about upright straight running at speed v, roll and steer obey the benchmark's
M q'' + v C1 q' + (g K0 + v^2 K2) q = 0: weave speed 4.2924 m/s, capsize speed 6.0243 m/s
(apps/bicycle_eigenvalues.cpp prints the eigenvalues).
"""
from gencoord import Frame, Matrix, Model, axis_angle, cos, rotation_x, rotation_y, rotation_z, sin

model = Model(dim=3)
x = model.coordinate("x", "rear contact point, x (m)")
y = model.coordinate("y", "rear contact point, y: to the right of the initial heading (m)")
psi = model.coordinate("psi", "yaw of the rear frame, to the right (rad)")
phi = model.coordinate("phi", "roll of the rear frame, to the right (rad)")
theta = model.coordinate("theta", "pitch of the rear frame, nose down; set by the front "
                         "contact (rad)")
theta_r = model.coordinate("theta_r", "rear wheel rotation angle (rad)")
delta = model.coordinate("delta", "steer angle, to the right (rad)")
theta_f = model.coordinate("theta_f", "front wheel rotation angle (rad)")

w = model.parameter("w", 1.02, "wheel base (m)")
c = model.parameter("c", 0.08, "trail (m)")
lam = model.parameter("lam", 0.3141592653589793, "steer axis tilt from vertical, pi/10 (rad)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
r_r = model.parameter("r_r", 0.3, "rear wheel radius (m)")
m_r = model.parameter("m_r", 2.0, "rear wheel mass (kg)")
I_rxx = model.parameter("I_rxx", 0.0603, "rear wheel moment of inertia about a diameter (kg m^2)")
I_ryy = model.parameter("I_ryy", 0.12, "rear wheel moment of inertia about its axle (kg m^2)")
x_b = model.parameter("x_b", 0.3, "rear frame centre of mass, x (m)")
z_b = model.parameter("z_b", -0.9, "rear frame centre of mass, z (down) (m)")
m_b = model.parameter("m_b", 85.0, "rear frame and rider mass (kg)")
I_bxx = model.parameter("I_bxx", 9.2, "rear frame inertia, xx (kg m^2)")
I_bxz = model.parameter("I_bxz", 2.4, "rear frame inertia, xz (kg m^2)")
I_byy = model.parameter("I_byy", 11.0, "rear frame inertia, yy (kg m^2)")
I_bzz = model.parameter("I_bzz", 2.8, "rear frame inertia, zz (kg m^2)")
x_h = model.parameter("x_h", 0.9, "front frame centre of mass, x (m)")
z_h = model.parameter("z_h", -0.7, "front frame centre of mass, z (down) (m)")
m_h = model.parameter("m_h", 4.0, "front frame mass (kg)")
I_hxx = model.parameter("I_hxx", 0.05892, "front frame inertia, xx (kg m^2)")
I_hxz = model.parameter("I_hxz", -0.00756, "front frame inertia, xz (kg m^2)")
I_hyy = model.parameter("I_hyy", 0.06, "front frame inertia, yy (kg m^2)")
I_hzz = model.parameter("I_hzz", 0.00708, "front frame inertia, zz (kg m^2)")
r_f = model.parameter("r_f", 0.35, "front wheel radius (m)")
m_f = model.parameter("m_f", 3.0, "front wheel mass (kg)")
I_fxx = model.parameter("I_fxx", 0.1405, "front wheel moment of inertia about a diameter (kg m^2)")
I_fyy = model.parameter("I_fyy", 0.28, "front wheel moment of inertia about its axle (kg m^2)")

# the paper's axes (z down) to the model's (z up): a half turn about x, its own inverse
T = Matrix.diag(1, -1, -1)


def frame(rotation, origin):
    """A frame built in the paper's axes, in the model's."""
    return Frame(T * rotation * T, T * origin)


def inertia(xx, yy, zz, xz=0):
    """A tensor in the paper's body axes, in the body axes as the model turns them."""
    return T * Matrix([[xx, 0, xz], [0, yy, 0], [xz, 0, zz]]) * T


yaw_roll = rotation_z(psi) * rotation_x(phi)
rear_frame = yaw_roll * rotation_y(theta)
rear_centre = Matrix([x, y, 0]) + yaw_roll * Matrix([0, 0, -r_r])
# the steer axis, pointing down and forward, meets the ground c ahead of the front contact
steer_axis = Matrix([sin(lam), 0, cos(lam)])
steer_point = rear_centre + rear_frame * Matrix([w + c, 0, r_r])
front_frame = rear_frame * axis_angle(steer_axis, delta)
front_centre = steer_point + front_frame * Matrix([-c, 0, -r_f])

rear_wheel = model.body("rear_wheel", mass=m_r, inertia=inertia(I_rxx, I_ryy, I_rxx),
                        frame=frame(rear_frame * rotation_y(theta_r), rear_centre))
rear_body_centre = Matrix([x_b, 0, z_b + r_r])  # from the rear wheel's centre, rear frame axes
rear_body = model.body("rear_frame", mass=m_b, inertia=inertia(I_bxx, I_byy, I_bzz, I_bxz),
                       frame=frame(rear_frame, rear_centre + rear_frame * rear_body_centre))
front_body_centre = Matrix([x_h - w - c, 0, z_h])  # from the steer point, front frame axes
front_body = model.body("front_frame", mass=m_h, inertia=inertia(I_hxx, I_hyy, I_hzz, I_hxz),
                        frame=frame(front_frame, steer_point + front_frame * front_body_centre))
front_wheel = model.body("front_wheel", mass=m_f, inertia=inertia(I_fxx, I_fyy, I_fxx),
                         frame=frame(front_frame * rotation_y(theta_f), front_centre))
model.gravity([0, 0, -g])
model.rolling_wheel(rear_wheel, r_r, axle=[0, 1, 0], name="rear_rolling")
model.rolling_wheel(front_wheel, r_f, axle=[0, 1, 0], name="front_rolling")

# The three hinges (each two points of its axis, 0.1 m apart), which the coordinates already
# keep, restated for the maximal-coordinate model (gencoord crosscheck), where every body
# moves freely. Offsets are from each body's centre of mass in the paper's axes (T maps them).
for side, sign in (("left", 1), ("right", -1)):
    along_axle = Matrix([0, 0.05 * sign, 0])
    along_steer = 0.05 * sign * steer_axis
    model.pin(rear_wheel.point(T * along_axle, name=f"rear_hub_{side}"),
              rear_body.point(T * (along_axle - rear_body_centre), name=f"rear_dropout_{side}"),
              name=f"rear_axle_{side}")
    model.pin(rear_body.point(T * (Matrix([w + c, 0, r_r]) + along_steer - rear_body_centre),
                              name=f"head_tube_{side}"),
              front_body.point(T * (along_steer - front_body_centre), name=f"steerer_{side}"),
              name=f"steer_axis_{side}")
    model.pin(front_wheel.point(T * along_axle, name=f"front_hub_{side}"),
              front_body.point(T * (Matrix([-c, 0, -r_f]) + along_axle - front_body_centre),
                               name=f"fork_end_{side}"),
              name=f"front_axle_{side}")
