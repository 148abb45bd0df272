"""The free-floating trunk with one leg of floating_leg.urdf, in the Y-Z-X Euler chart only.

floating_leg.py's twin in the other chart of the atlas: load_urdf takes the free base's
chart from the model's, so MuJoCo's free joint is compared with each chart on its own.
"""
from gencoord import Model, load_urdf

model = Model(dim=3, chart="yzx")
load_urdf(model, "floating_leg.urdf")
