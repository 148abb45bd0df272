r"""Four-bar linkage: a crank, a coupler and a rocker between two ground pivots, in a vertical
plane, closed by a loop constraint.

               B o-------------o C
                /   coupler b   \
       crank a /                 \ rocker c
              /                   \
   ground  A o ------- d --------- o D

Each bar is a uniform rigid bar (mass m_i, length l_i, moment of inertia m_i l_i^2 / 12 about
its middle). The coordinates are the three bars' absolute angles from the +x axis; the chain
A-B-C is a tree, and the loop closes where the rocker's tip meets the coupler's end C: two
holonomic constraints, so one degree of freedom is left. A motor at A drives the crank with
the input torque `u`.
"""
from gencoord import Frame, Model, cos, sin

model = Model(dim=2)
crank = model.coordinate("crank", "angle of the crank AB from the +x axis (rad)", initial=1.2)
coupler = model.coordinate("coupler", "angle of the coupler BC from the +x axis (rad)",
                           initial=0.3863)
rocker = model.coordinate("rocker", "angle of the rocker DC from the +x axis (rad)",
                          initial=1.3185)
a = model.parameter("a", 0.3, "crank length AB (m)")
b = model.parameter("b", 0.8, "coupler length BC (m)")
c = model.parameter("c", 0.6, "rocker length DC (m)")
d = model.parameter("d", 0.7, "ground length AD (m)")
m_a = model.parameter("m_a", 0.5, "crank mass (kg)")
m_b = model.parameter("m_b", 1.2, "coupler mass (kg)")
m_c = model.parameter("m_c", 0.9, "rocker mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
u = model.input("u", "motor torque on the crank at A (N m)")


def bar(name, mass, length, angle, start, joint):
    """A uniform bar from `start` along `angle`, its start pinned to `joint` (a point, or a
    fixed position); returns its far end, a point on it."""
    middle = [start[0] + length / 2 * cos(angle), start[1] + length / 2 * sin(angle)]
    body = model.body(name, mass=mass, inertia=mass * length**2 / 12,
                      frame=Frame(angle, middle))
    model.pin(body.point([-length / 2, 0], name=f"{name}_end"), joint, name=f"{name}_joint")
    return body.point([length / 2, 0], name=f"{name}_tip")


# the pins restate the tree's joints, which the coordinates already keep, for the
# maximal-coordinate model (gencoord crosscheck), where every bar moves freely
crank_tip = bar("crank_bar", m_a, a, crank, [0, 0], [0, 0])
coupler_tip = bar("coupler_bar", m_b, b, coupler, [a * cos(crank), a * sin(crank)], crank_tip)
rocker_tip = bar("rocker_bar", m_c, c, rocker, [d, 0], [d, 0])
model.close_loop(coupler_tip, rocker_tip, name="loop_C")
model.generalized_force(crank, u, name="motor")
model.gravity([0, -g])
