r"""A compound (physical) pendulum: a rigid bar swinging in a vertical plane about a pivot.

        pivot o
               \  d
                \
                 * centre of mass (m, I_c)
                  \

theta is the angle of the line from the pivot to the centre of mass, from the downward
vertical. The bar has mass m and moment of inertia I_c about its centre of mass, and the pivot
is a distance d from it, so the moment of inertia about the pivot is I_c + m d^2 and small
swings have the period 2 pi sqrt((I_c + m d^2) / (m g d)).
"""
from gencoord import Frame, Model, cos, sin

model = Model(dim=2)
theta = model.coordinate("theta", "angle of the bar from the downward vertical (rad)",
                         initial=0.3)
m = model.parameter("m", 2.0, "mass of the bar (kg)")
I_c = model.parameter("I_c", 0.1, "moment of inertia about the centre of mass (kg m^2)")
d = model.parameter("d", 0.4, "distance from the pivot to the centre of mass (m)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")

# body axes turn with the bar; the pivot is at (0, d) in them
bar = model.body("bar", mass=m, inertia=I_c, frame=Frame(theta, [d * sin(theta), -d * cos(theta)]))
model.pin(bar.point([0, d], name="pivot_point"), [0, 0], name="pivot")
model.gravity([0, -g])
