"""Positions a user writes with tan, 1/q and sqrt: a bead on a slider s, an arm at angle a."""
from gencoord import Model, sqrt, tan

model = Model(dim=2)
s = model.coordinate("s", "slider position (m)", initial=0.5)
a = model.coordinate("a", "arm angle (rad)", initial=0.3)
bead = model.particle("bead", mass=1, position=[sqrt(1 - s**2), s])
arm = model.particle("arm", mass=1, position=[tan(a), 1 / (2 + s)])
pivot = model.fixed_point("pivot", [0, 0])
model.gravity([0, -9.81])
model.rod(pivot, bead, 1)
