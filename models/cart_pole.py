r"""Cart-pole: a cart on a horizontal track carrying a pendulum pole (point mass at its tip).

               o tip (m_pole)
              /
             / l     theta: pole angle from the upward vertical
            /
      +----+----+
      |  cart   | --> force u (a generalized force on s)
      +--o---o--+
    ==============> s

Cart at (s, 0); tip at (s + l sin(theta), l cos(theta)). theta = 0 is the inverted
(unstable) equilibrium.
"""
from gencoord import Model, cos, sin

model = Model(dim=2)
s = model.coordinate("s", "cart position along the track (m)")
theta = model.coordinate("theta", "pole angle from the upward vertical (rad)",
                         initial=0.2)
l = model.parameter("l", 0.5, "pole length (m)")
m_cart = model.parameter("m_cart", 1.0, "cart mass (kg)")
m_pole = model.parameter("m_pole", 0.1, "pole tip mass (kg)")
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
u = model.input("u", "horizontal force applied to the cart (N)")

cart = model.particle("cart", mass=m_cart, position=[s, 0])
tip = model.particle("tip", mass=m_pole, position=[s + l * sin(theta), l * cos(theta)])
model.gravity([0, -g])
model.generalized_force(s, u, name="cart force")
model.plane(cart, normal=[0, 1], offset=0)
model.rod(cart, tip, l)
