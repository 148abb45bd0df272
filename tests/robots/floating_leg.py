"""The free-floating trunk with one leg of floating_leg.urdf, in the Z-Y-X Euler chart only.

`./generate floating_leg.urdf` would build the atlas of both Euler charts; MuJoCo's free
joint is compared with the zyx chart alone, so this file loads the URDF into one chart.
"""
from generator import Model, load_urdf

model = Model(dim=3, chart="zyx")
load_urdf(model, "floating_leg.urdf")
