"""A branched pendulum on a shaken pivot, for the recursive kernels' tests: a spherical
pendulum whose bob carries a rigidly attached lamp and two planar pendulums, the two tips
joined by a spring, one arm damped against the bob and one angle sprung. Every kind of tree
node and force the recursions handle appears once. Every number is a parameter, so tests can
evaluate the model in any precision."""
from gencoord import Model, cos, sin

model = Model(dim=3)
t = model.t
polar = model.coordinate("polar", "angle of the upper rod from the downward vertical (rad)",
                         initial=0.4)
azimuth = model.coordinate("azimuth", "azimuth of the upper rod (rad)", initial=0.2)
left = model.coordinate("left", "angle of the left arm in the x-y plane (rad)", initial=0.3)
right = model.coordinate("right", "angle of the right arm in the y-z plane (rad)",
                         initial=-0.5)
length = model.parameter("length", 1.2, "upper rod length (m)")
arm = model.parameter("arm", 0.6, "arm length (m)")
amplitude = model.parameter("amplitude", 0.05, "pivot shaking amplitude (m)")
omega = model.parameter("omega", 7.0, "pivot shaking frequency (rad/s)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
m_upper = model.parameter("m_upper", 2.0, "mass of the upper bob (kg)")
m_lamp = model.parameter("m_lamp", 0.3, "mass of the lamp (kg)")
m_left = model.parameter("m_left", 0.5, "mass of the left tip (kg)")
m_right = model.parameter("m_right", 0.7, "mass of the right tip (kg)")
drop = model.parameter("drop", 0.1, "how far the lamp hangs below the upper bob (m)")
k_tips = model.parameter("k_tips", 20.0, "stiffness of the spring between the tips (N)")
c_tips = model.parameter("c_tips", 0.3, "damping of that spring (N s)")
rest_tips = model.parameter("rest_tips", 0.8, "rest length of that spring (m)")
c_arm = model.parameter("c_arm", 0.4, "damper between upper bob and left tip (N s/m)")
k_right = model.parameter("k_right", 3.0, "joint spring on the right angle (N m/rad)")
rest_right = model.parameter("rest_right", 0.1, "rest angle of that spring (rad)")
c_right = model.parameter("c_right", 0.2, "damping of that spring (N m s/rad)")

pivot = [0, amplitude * cos(omega * t), 0]
bob = [pivot[0] + length * sin(polar) * cos(azimuth),
       pivot[1] - length * cos(polar),
       pivot[2] + length * sin(polar) * sin(azimuth)]
upper = model.particle("upper", mass=m_upper, position=bob)
lamp = model.particle("lamp", mass=m_lamp, position=[bob[0], bob[1] - drop, bob[2]])
tip_left = model.particle("tip_left", mass=m_left,
                          position=[bob[0] + arm * sin(left), bob[1] - arm * cos(left), bob[2]])
tip_right = model.particle("tip_right", mass=m_right,
                           position=[bob[0], bob[1] - arm * cos(right),
                                     bob[2] + arm * sin(right)])
model.fixed_point("pivot", pivot)
model.spring(tip_left, tip_right, stiffness=k_tips, rest_length=rest_tips, damping=c_tips)
model.damper(upper, tip_left, c_arm)
model.joint_spring(right, stiffness=k_right, rest=rest_right, damping=c_right)
model.gravity([0, -g, 0])
