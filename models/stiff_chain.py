r"""Stiff chain: a planar n-link chain with stiff, damped joint springs (relative angles).

      pivot o
             \  joint 1: spring k (phi1), damper c
              o m
              |  joint 2: spring k (phi2)
              o m
               \ ...

phi<k> is the angle of link k relative to link k-1 (phi1 relative to the downward
vertical). With a large k the joint frequencies sqrt(k / (m l^2)) make explicit integrators
take tiny steps; implicit ones do not need to. `--set n=N` (default 10).
"""
from gencoord import Model, cos, sin

model = Model(dim=2)
n = model.option("n", 10, "number of links", minimum=1)
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
l = model.parameter("l", 0.2, "length of every link (m)")
m = model.parameter("m", 0.1, "mass at the end of every link (kg)")
k = model.parameter("k", 1000.0, "joint spring stiffness (N m/rad)")
c = model.parameter("c", 0.01, "joint damping (N m s/rad)")

previous = model.fixed_point("pivot", [0, 0])
x, y, angle = 0, 0, 0
for j in range(1, n + 1):
    phi = model.coordinate(f"phi{j}", f"angle of link {j} relative to link {j - 1} (rad)",
                           initial=0.3 if j == 1 else 0.0)
    angle = angle + phi
    x, y = x + l * sin(angle), y - l * cos(angle)
    bob = model.particle(f"bob{j}", mass=m, position=[x, y])
    model.rod(previous, bob, l)
    model.joint_spring(phi, k, rest=0, damping=c)
    previous = bob
model.gravity([0, -g])
