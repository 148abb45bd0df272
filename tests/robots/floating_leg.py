"""The free-floating trunk with one leg of floating_leg.urdf, in the Z-Y-X Euler chart only.

`./generate floating_leg.urdf` would build the atlas of both Euler charts; MuJoCo's free
joint is compared with each chart on its own, so this file loads the URDF into the zyx chart
and floating_leg_yzx.py into the yzx chart.
"""
from gencoord import Model, load_urdf

model = Model(dim=3, chart="zyx")
load_urdf(model, "floating_leg.urdf")
