r"""Slider-crank: a crank turning about a fixed pivot drives a slider along a straight guide
through a connecting rod, in a vertical plane (an engine's piston or a pump's plunger).

                 B
                 o
       crank a  / \   rod b
               /   \
   pivot A    o     \ [slider] ---- guide, the x axis
                     C

The crank and the rod are uniform bars (mass m_i, length l_i, moment of inertia
m_i l_i^2 / 12 about the middle); the slider is a point mass on the x axis through A. The
coordinates are the crank's and the rod's absolute angles and the slider's position; the
rod's end must be at the slider: two holonomic constraints (a closed loop, model.close_loop),
one degree of freedom left. A motor at A drives the crank with the torque `u`; the gas (or
the load) pushes the slider with the force `p`.

The loop has a closed form, s = a cos(crank) + sqrt(b^2 - a^2 sin(crank)^2) for b > a, which
a model written in the crank angle alone uses; the constrained model must follow it.
"""
from gencoord import Frame, Model, cos, sin

model = Model(dim=2)
crank = model.coordinate("crank", "angle of the crank AB from the +x axis (rad)", initial=0.8)
rod = model.coordinate("rod", "angle of the rod BC from the +x axis (rad)", initial=-0.216903614726)
s = model.coordinate("s", "slider position along the guide (m)", initial=0.592790252896)
a = model.parameter("a", 0.15, "crank length AB (m)")
b = model.parameter("b", 0.5, "rod length BC (m)")
m_a = model.parameter("m_a", 1.0, "crank mass (kg)")
m_b = model.parameter("m_b", 0.8, "rod mass (kg)")
m_s = model.parameter("m_s", 1.5, "slider mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
u = model.input("u", "motor torque on the crank at A (N m)")
p = model.input("p", "force on the slider along +x (N)")

crank_end = [a * cos(crank), a * sin(crank)]
crank_bar = model.body("crank_bar", mass=m_a, inertia=m_a * a**2 / 12,
                       frame=Frame(crank, [a / 2 * cos(crank), a / 2 * sin(crank)]))
rod_bar = model.body("rod_bar", mass=m_b, inertia=m_b * b**2 / 12,
                     frame=Frame(rod, [crank_end[0] + b / 2 * cos(rod),
                                       crank_end[1] + b / 2 * sin(rod)]))
slider = model.particle("slider", mass=m_s, position=[s, 0])
model.close_loop(rod_bar.point([b / 2, 0], name="rod_tip"), slider, name="loop_C")
# the joints and the guide, which the coordinates already keep, restated for the
# maximal-coordinate model (gencoord crosscheck), where every part moves freely
model.pin(crank_bar.point([-a / 2, 0], name="crank_pivot"), [0, 0], name="pivot_A")
model.pin(rod_bar.point([-b / 2, 0], name="rod_end"),
          crank_bar.point([a / 2, 0], name="crank_tip"), name="pin_B")
model.plane(slider, [0, 1], name="guide")
model.generalized_force(crank, u, name="motor")
model.generalized_force(s, p, name="gas")
model.gravity([0, -g])
