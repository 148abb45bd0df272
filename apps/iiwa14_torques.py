r"""The KUKA LBR iiwa 14 of models/iiwa14.urdf with a motor torque on each of its seven joints,
as control inputs (tau1 ... tau7, N m), for apps/arm_reach.cpp's trajectory optimization."""
from gencoord import Model, load_urdf

model = Model(dim=3)
links = load_urdf(model, "../models/iiwa14.urdf")
for k in range(1, 8):
    torque = model.input(f"tau{k}", f"motor torque of joint {k} (N m)")
    model.generalized_force(links.coordinates[f"iiwa_joint_{k}"], torque, name=f"motor {k}")
