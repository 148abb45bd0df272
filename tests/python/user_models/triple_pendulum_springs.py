"""A triple pendulum with springs between the bobs, written as a new user would."""
from gencoord import Model, cos, sin

model = Model(dim=2)
theta1 = model.coordinate("theta1", "first rod angle (rad)", initial=0.5)
theta2 = model.coordinate("theta2", "second rod angle relative to the first (rad)")
theta3 = model.coordinate("theta3", "third rod angle relative to the second (rad)")
l1 = model.parameter("l1", 1.0, "first rod length (m)")
l2 = model.parameter("l2", 0.8, "second rod length (m)")
l3 = model.parameter("l3", 0.6, "third rod length (m)")
m1 = model.parameter("m1", 1.0, "first bob mass (kg)")
m2 = model.parameter("m2", 0.8, "second bob mass (kg)")
m3 = model.parameter("m3", 0.5, "third bob mass (kg)")
k = model.parameter("k", 20.0, "spring stiffness (N)")
L = model.parameter("L", 1.2, "spring rest length (m)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")

pivot = model.fixed_point("pivot", [0, 0])
x1 = [l1 * sin(theta1), -l1 * cos(theta1)]
x2 = [x1[0] + l2 * sin(theta1 + theta2), x1[1] - l2 * cos(theta1 + theta2)]
x3 = [x2[0] + l3 * sin(theta1 + theta2 + theta3),
      x2[1] - l3 * cos(theta1 + theta2 + theta3)]
bob1 = model.particle("bob1", mass=m1, position=x1)
bob2 = model.particle("bob2", mass=m2, position=x2)
bob3 = model.particle("bob3", mass=m3, position=x3)
model.gravity([0, -g])
model.spring(bob1, bob2, k, L, damping=0.1)
model.spring(bob2, bob3, k, L, damping=0.1)
model.spring(bob1, bob3, k, L)
model.rod(pivot, bob1, l1)
model.rod(bob1, bob2, l2)
model.rod(bob2, bob3, l3)
