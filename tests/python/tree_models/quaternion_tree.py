"""A free-floating body with a ball-jointed arm and a revolute hand, for the tests of free and
ball joints (unit quaternions, speeds that are not rates): the recursions against the dense
derivation, and the structure of the tree. A spring pulls the hand towards a fixed anchor, the
arm takes a body torque that depends on time and on the base's speed, and the hand's joint is
damped. Geometry and inertias are exact (rationals), masses parameters, so tests can evaluate
the model in any precision."""
from gencoord import Ball, Free, Model, Origin, Rational, Revolute, add_link, sin

R = Rational
model = Model(dim=3)
t = model.t
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
m_base = model.parameter("m_base", 3.0, "base mass (kg)")
m_arm = model.parameter("m_arm", 1.0, "arm mass (kg)")
m_hand = model.parameter("m_hand", 0.5, "hand mass (kg)")
k = model.parameter("k", 20.0, "stiffness of the hand's spring (N)")


def box(a, b, c):
    """A principal inertia diag(a, b, c) with a general orientation's products."""
    return [[a, R(1, 500), R(-1, 800)], [R(1, 500), b, R(1, 600)], [R(-1, 800), R(1, 600), c]]


base = add_link(model, "base", None, Free(Origin(xyz=[0, 0, 1], rpy=[R(1, 10), R(1, 5), 0])),
                mass=m_base, inertia=box(R(1, 10), R(1, 5), R(1, 4)),
                com=Origin(xyz=[R(1, 100), R(1, 50), R(3, 100)]))
arm = add_link(model, "arm", base, Ball(Origin(xyz=[0, 0, R(-1, 5)], rpy=[0, R(1, 3), 0])),
               mass=m_arm, inertia=box(R(1, 50), R(3, 100), R(1, 25)),
               com=Origin(xyz=[0, R(1, 10), R(-3, 10)], rpy=[R(1, 5), 0, R(-1, 4)]))
hand = add_link(model, "hand", arm,
                Revolute([0, 1, 0], Origin(xyz=[0, R(1, 10), R(-1, 2)]), damping=R(1, 5)),
                mass=m_hand, inertia=box(R(1, 100), R(1, 100), R(3, 200)),
                com=Origin(xyz=[R(1, 10), 0, R(-1, 10)]))
model.gravity([0, 0, -g])
anchor = model.fixed_point("anchor", [R(1, 2), 0, 0])
model.spring(anchor, hand.body.point([0, 0, R(-1, 5)], name="grip"), k, R(1, 2))
model.torque(arm.body, [R(1, 10) * sin(3 * t), R(1, 20) * base.speeds[0], 0], name="twist")
