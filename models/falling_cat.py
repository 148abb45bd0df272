r"""Falling cat (or diver): a free-floating planar body of three links, no gravity.

           front o                      root: position (x, y) and orientation psi of the
                  \  l_front                  middle link's centre and direction
                   \ joint angle alpha
       rear o-------o-------o           joint angles alpha (front) and beta (rear) are
              l_rear  body    \               meant to be scripted
                 beta         \

Five coordinates: x, y, psi (free) and alpha, beta (scripted at runtime). With the joint
angles driven through a closed cycle, the total angular momentum stays zero, yet the body
comes back rotated: a geometric phase, how a cat rights itself.
"""
from gencoord import Model, cos, sin

model = Model(dim=2)
x = model.coordinate("x", "centre of the middle link, horizontal (m)")
y = model.coordinate("y", "centre of the middle link, vertical (m)")
psi = model.coordinate("psi", "orientation of the middle link (rad)")
alpha = model.coordinate("alpha", "front joint angle (rad)", initial=0.5)
beta = model.coordinate("beta", "rear joint angle (rad)", initial=-0.5)
L = model.parameter("L", 1.0, "length of the middle link (m)")
l_front = model.parameter("l_front", 0.6, "length of the front link (m)")
l_rear = model.parameter("l_rear", 0.6, "length of the rear link (m)")
m_body = model.parameter("m_body", 1.0, "mass at each end of the middle link (kg)")
m_front = model.parameter("m_front", 0.5, "mass at the front tip (kg)")
m_rear = model.parameter("m_rear", 0.5, "mass at the rear tip (kg)")

ex, ey = cos(psi), sin(psi)
shoulder = model.particle("shoulder", mass=m_body, position=[x + L / 2 * ex, y + L / 2 * ey])
hip = model.particle("hip", mass=m_body, position=[x - L / 2 * ex, y - L / 2 * ey])
front = model.particle("front", mass=m_front,
                       position=[x + L / 2 * ex + l_front * cos(psi + alpha),
                                 y + L / 2 * ey + l_front * sin(psi + alpha)])
rear = model.particle("rear", mass=m_rear,
                      position=[x - L / 2 * ex - l_rear * cos(psi + beta),
                                y - L / 2 * ey - l_rear * sin(psi + beta)])
model.rod(hip, shoulder, L)
model.rod(shoulder, front, l_front)
model.rod(hip, rear, l_rear)
