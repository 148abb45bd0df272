r"""Double pendulum: two point masses on massless rigid rods, absolute angles.

      pivot o
            |\
            | \ l1
     theta1 |  \
            |   o m1
            |   |\
            |   | \ l2
            theta2 \
                |   o m2

x1 = l1 (sin(theta1), -cos(theta1)),  x2 = x1 + l2 (sin(theta2), -cos(theta2)).
The textbook equations of motion (e.g. Goldstein; with d = theta1 - theta2):
  (m1 + m2) l1 a1 + m2 l2 cos(d) a2 + m2 l2 sin(d) w2^2 + (m1 + m2) g sin(theta1) = 0
  l2 a2 + l1 cos(d) a1 - l1 sin(d) w1^2 + g sin(theta2) = 0
"""
from gencoord import Model, cos, sin

model = Model(dim=2)
theta1 = model.coordinate("theta1", "angle of the first rod from the downward vertical (rad)",
                          initial=1.5707963267948966)
theta2 = model.coordinate("theta2", "angle of the second rod from the downward vertical (rad)")
l1 = model.parameter("l1", 1.0, "first rod length (m)")
l2 = model.parameter("l2", 1.0, "second rod length (m)")
m1 = model.parameter("m1", 1.0, "first bob mass (kg)")
m2 = model.parameter("m2", 1.0, "second bob mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")

pivot = model.fixed_point("pivot", [0, 0])
x1 = [l1 * sin(theta1), -l1 * cos(theta1)]
bob1 = model.particle("bob1", mass=m1, position=x1)
bob2 = model.particle("bob2", mass=m2, position=[x1[0] + l2 * sin(theta2),
                                                 x1[1] - l2 * cos(theta2)])
model.gravity([0, -g])
model.rod(pivot, bob1, l1)
model.rod(bob1, bob2, l2)
