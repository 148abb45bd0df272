r"""A tumbling trunk with a ball-jointed arm and a damped revolute hand (test model): unit
quaternions in q and speeds that are not rates (nq = 12, nv = 10), so the maximal model's
inverse map steps along the speeds (retract) and maps the hand's damping torque, a
generalized force, through M J Mt^-1. Each body is four point masses held rigid by six rods;
the ball joint is one pin, the hand's hinge two.
"""
from gencoord import Ball, Free, Model, Origin, Revolute, add_link

model = Model(dim=3)
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
c = model.parameter("c", 0.05, "hand joint damping (N m s/rad)")

trunk = add_link(model, "trunk", None, Free(Origin(xyz=[0, 0, 1], rpy=[0.1, 0.2, 0])), mass=4.0,
                 inertia=[[0.12, 0.002, 0], [0.002, 0.2, 0.001], [0, 0.001, 0.25]],
                 com=Origin(xyz=[0.01, 0.02, 0.03]))
arm = add_link(model, "arm", trunk, Ball(Origin(xyz=[0, 0, -0.2], rpy=[0, 0.3, 0])), mass=1.0,
               inertia=[[0.02, 0, 0.001], [0, 0.03, 0], [0.001, 0, 0.04]],
               com=Origin(xyz=[0, 0.1, -0.3]))
hand = add_link(model, "hand", arm, Revolute([0, 1, 0], Origin(xyz=[0, 0.1, -0.5]), damping=c),
                mass=0.5,
                inertia=[[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.015]],
                com=Origin(xyz=[0.1, 0, -0.1]))
model.gravity([0, 0, -g])
