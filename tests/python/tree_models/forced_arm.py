"""A branched arm of rigid bodies, for the rigid-body recursions' tests: a turret, a slider on
an oblique rail, a massless wrist, a hand with an offset, tilted centre of mass, a tool
welded to it, and a damped side arm on the turret. A spring pulls the hand towards a shaken
anchor, a damper joins the side arm to the slider, the hand takes a body torque that
depends on time and rates, and the slide has a joint spring. Every kind of link, joint and
force the recursions handle appears once. Masses and force constants are parameters and the
geometry is exact (rationals), so tests can evaluate the model in any precision."""
from gencoord import Continuous, Fixed, Model, Origin, Prismatic, Rational, Revolute
from gencoord import add_link, cos, sin

R = Rational
model = Model(dim=3)
t = model.t
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
m_turret = model.parameter("m_turret", 3.0, "turret mass (kg)")
m_slider = model.parameter("m_slider", 1.5, "slider mass (kg)")
m_hand = model.parameter("m_hand", 0.8, "hand mass (kg)")
m_tool = model.parameter("m_tool", 0.3, "tool mass (kg)")
m_side = model.parameter("m_side", 0.6, "side arm mass (kg)")
k_anchor = model.parameter("k_anchor", 40.0, "stiffness of the hand's spring (N)")
c_link = model.parameter("c_link", 0.7, "damper between side arm and slider (N s/m)")
k_slide = model.parameter("k_slide", 5.0, "joint spring on the slide (N/m)")
spin = model.parameter("spin", 0.2, "amplitude of the hand's torque (N m)")
omega = model.parameter("omega", 3.0, "frequency of the anchor and the torque (rad/s)")


def box(a, b, c):
    """A principal inertia diag(a, b, c) with a general orientation's products."""
    return [[a, R(1, 500), R(-1, 800)], [R(1, 500), b, R(1, 600)], [R(-1, 800), R(1, 600), c]]


turret = add_link(model, "turret", None,
                  Revolute([0, 0, 1], Origin(xyz=[0, 0, R(1, 10)]), name="yaw"),
                  mass=m_turret, inertia=box(R(1, 5), R(1, 5), R(1, 10)),
                  com=Origin(xyz=[R(1, 50), 0, R(1, 5)]))
slider = add_link(model, "slider", turret,
                  Prismatic([1, 0, 1], Origin(xyz=[R(1, 10), 0, R(3, 10)],
                                              rpy=[R(3, 10), 0, R(1, 5)]), name="slide"),
                  mass=m_slider, inertia=box(R(1, 20), R(1, 15), R(1, 25)),
                  com=Origin(xyz=[0, R(1, 20), 0]))
wrist = add_link(model, "wrist", slider,
                 Revolute([0, 1, 0], Origin(xyz=[R(1, 5), 0, 0]), name="bend"))
hand = add_link(model, "hand", wrist,
                Revolute([1, 1, 0], Origin(xyz=[0, 0, R(1, 4)], rpy=[0, R(1, 2), 0]),
                         name="twist"),
                mass=m_hand, inertia=box(R(1, 30), R(1, 40), R(1, 35)),
                com=Origin(xyz=[R(1, 10), R(-1, 20), R(1, 8)], rpy=[R(1, 5), R(-1, 3), R(2, 5)]))
add_link(model, "tool", hand, Fixed(Origin(xyz=[0, 0, R(1, 5)], rpy=[R(1, 2), 0, 0])),
         mass=m_tool, inertia=box(R(1, 100), R(1, 90), R(1, 80)),
         com=Origin(xyz=[0, 0, R(1, 20)]))
side = add_link(model, "side", turret,
                Continuous([1, 0, 0], Origin(xyz=[0, R(1, 5), R(1, 5)]), damping=R(1, 4),
                           name="roll"),
                mass=m_side, inertia=box(R(1, 40), R(1, 45), R(1, 50)),
                com=Origin(xyz=[0, R(1, 4), 0]))

model.gravity([0, 0, -g])
anchor = model.fixed_point("anchor", [R(1, 2) + R(1, 10) * sin(omega * t), R(1, 5), 1])
model.spring(anchor, hand.body.point([0, 0, R(1, 10)], name="grip"), k_anchor, R(3, 10))
model.damper(side.body.point([0, R(1, 5), 0], name="side_tip"),
             slider.body.point([R(1, 10), 0, 0], name="slider_tip"), c_link)
model.torque(hand.body, [spin * cos(omega * t), 0, -R(1, 10) * model.rate(hand.coordinate)])
model.joint_spring(slider.coordinate, k_slide, rest=R(1, 10))
