r"""Double inverted pendulum on a cart: a cart on a horizontal track carrying two poles in
series, each a massless rod with a point mass at its tip.

                o bob 2 (m2)
               /
              / l2     theta2: upper pole's angle from the upward vertical
             o bob 1 (m1)
            /
           / l1        theta1: lower pole's angle from the upward vertical
      +---+-----+
      |  cart   | --> force u (a generalized force on s)
      +--o---o--+
    ==============> s

Cart at (s, 0); bob 1 at (s + l1 sin(theta1), l1 cos(theta1)); bob 2 at bob 1 plus
(l2 sin(theta2), l2 cos(theta2)). theta1 = theta2 = 0 is the upright (unstable)
equilibrium, which docs/python.md's LQR example stabilizes.
"""
from gencoord import Model, cos, sin

model = Model(dim=2)
s = model.coordinate("s", "cart position along the track (m)")
theta1 = model.coordinate("theta1", "lower pole's angle from the upward vertical (rad)",
                          initial=0.2)
theta2 = model.coordinate("theta2", "upper pole's angle from the upward vertical (rad)")
l1 = model.parameter("l1", 0.5, "lower pole length (m)")
l2 = model.parameter("l2", 0.5, "upper pole length (m)")
m_cart = model.parameter("m_cart", 1.0, "cart mass (kg)")
m1 = model.parameter("m1", 0.1, "mass at the lower pole's tip (kg)")
m2 = model.parameter("m2", 0.1, "mass at the upper pole's tip (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
u = model.input("u", "horizontal force applied to the cart (N)")

bob1_x = [s + l1 * sin(theta1), l1 * cos(theta1)]
cart = model.particle("cart", mass=m_cart, position=[s, 0])
bob1 = model.particle("bob1", mass=m1, position=bob1_x)
bob2 = model.particle("bob2", mass=m2, position=[bob1_x[0] + l2 * sin(theta2),
                                                 bob1_x[1] + l2 * cos(theta2)])
model.gravity([0, -g])
model.generalized_force(s, u, name="cart force")
model.plane(cart, normal=[0, 1], offset=0)
model.rod(cart, bob1, l1)
model.rod(bob1, bob2, l2)
