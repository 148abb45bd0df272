r"""The slider-crank of models/slider_crank.py in its one independent coordinate: the rod's
angle and the slider's position are the loop's closed form in the crank angle, so this model
has no constraint. The constrained model must follow it (constrained_dynamics_test.cc)."""
from gencoord import Frame, Model, atan2, cos, sin, sqrt

model = Model(dim=2)
crank = model.coordinate("crank", "angle of the crank AB from the +x axis (rad)", initial=0.8)
a = model.parameter("a", 0.15, "crank length AB (m)")
b = model.parameter("b", 0.5, "rod length BC (m)")
m_a = model.parameter("m_a", 1.0, "crank mass (kg)")
m_b = model.parameter("m_b", 0.8, "rod mass (kg)")
m_s = model.parameter("m_s", 1.5, "slider mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
u = model.input("u", "motor torque on the crank at A (N m)")
p = model.input("p", "force on the slider along +x (N)")

reach = sqrt(b**2 - a**2 * sin(crank)**2)  # the rod's length along the guide
rod = atan2(-a * sin(crank), reach)
s = a * cos(crank) + reach
crank_end = [a * cos(crank), a * sin(crank)]
model.body("crank_bar", mass=m_a, inertia=m_a * a**2 / 12,
           frame=Frame(crank, [a / 2 * cos(crank), a / 2 * sin(crank)]))
model.body("rod_bar", mass=m_b, inertia=m_b * b**2 / 12,
           frame=Frame(rod, [crank_end[0] + b / 2 * cos(rod), crank_end[1] + b / 2 * sin(rod)]))
model.particle("slider", mass=m_s, position=[s, 0])
model.generalized_force(crank, u + p * s.diff(crank), name="motor and gas")
model.gravity([0, -g])
