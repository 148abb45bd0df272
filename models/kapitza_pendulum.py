r"""Kapitza pendulum: a pendulum whose pivot oscillates vertically, y_pivot = a cos(omega t).

         ^  pivot moves up and down: y = a cos(omega t)
         |
         o pivot
          \
           \ l      theta: angle from the downward vertical
            \
             o bob (m)

X depends on time explicitly. The inverted position theta = pi is stable when the drive is
fast and strong enough: a^2 omega^2 > 2 g l (Kapitza's criterion).
"""
from gencoord import Model, cos, sin

model = Model(dim=2)
theta = model.coordinate("theta", "angle from the downward vertical (rad)", initial=3.0)
l = model.parameter("l", 1.0, "rod length (m)")
m = model.parameter("m", 1.0, "bob mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
a = model.parameter("a", 0.1, "pivot oscillation amplitude (m)")
omega = model.parameter("omega", 100.0, "pivot oscillation angular frequency (rad/s)")

t = model.time
pivot = model.fixed_point("pivot", [0, a * cos(omega * t)])
bob = model.particle("bob", mass=m, position=[l * sin(theta), a * cos(omega * t) - l * cos(theta)])
model.gravity([0, -g])
model.rod(pivot, bob, l)
