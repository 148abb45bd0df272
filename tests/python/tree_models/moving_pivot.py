"""Two links whose first joint's pivot is shaken in time: a revolute joint whose origin moves,
for the rigid-body recursions' tests (its link velocity has a drift besides the axis)."""
from gencoord import Model, Origin, Rational, Revolute
from gencoord import add_link, sin

R = Rational
model = Model(dim=3)
t = model.t
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
upper = add_link(model, "upper", None,
                 Revolute([0, 1, 0], Origin(xyz=[0, 0, sin(3 * t) / 10])),
                 mass=2, inertia=[[R(1, 10), 0, 0], [0, R(1, 10), 0], [0, 0, R(1, 50)]],
                 com=Origin(xyz=[0, 0, R(-1, 4)]))
lower = add_link(model, "lower", upper, Revolute([1, 0, 0], Origin(xyz=[0, 0, R(-1, 2)])),
                 mass=1, inertia=[[R(1, 20), 0, 0], [0, R(1, 20), 0], [0, 0, R(1, 100)]],
                 com=Origin(xyz=[0, 0, R(-1, 5)]))
model.gravity([0, 0, -g])
