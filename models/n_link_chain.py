r"""Planar n-link chain (n-link pendulum): point masses on massless rods, absolute angles.

      pivot o
             \ l1
              o m1
              | l2
              o m2
               \ ...
                o mn

Link k has its own symbolic length l<k> and mass m<k>; theta<k> is its angle from the
downward vertical. Generate a variant with `./generate models/n_link_chain.py --set n=5`
(writes generated/n_link_chain_5.hpp, type NLinkChain5).
"""
from gencoord import Model, cos, sin

model = Model(dim=2)
n = model.option("n", 3, "number of links", minimum=1)
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")

previous = model.fixed_point("pivot", [0, 0])
x, y = 0, 0
for k in range(1, n + 1):
    theta = model.coordinate(f"theta{k}", f"angle of link {k} from the downward vertical (rad)",
                             initial=0.5)
    length = model.parameter(f"l{k}", 1.0, f"length of link {k} (m)")
    mass = model.parameter(f"m{k}", 1.0, f"mass at the end of link {k} (kg)")
    x, y = x + length * sin(theta), y - length * cos(theta)
    bob = model.particle(f"bob{k}", mass=mass, position=[x, y])
    model.rod(previous, bob, length)
    previous = bob
model.gravity([0, -g])
