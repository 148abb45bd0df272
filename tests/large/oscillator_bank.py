r"""A bank of independent oscillators (test model), large enough that the model's Mt and J pass
Eigen's stack limit for fixed-size objects, so the generated types are gencoord::HeapMatrix.

    anchor_i o--/\/\/\--o bob_i     at height i, moving along x only; i = 0 .. n-1

Bob i sits at (q_i, i) and hangs on a spring of stiffness k_i = k (1 + i / n), force per unit
strain, and rest length L from the anchor (-L, i): for q_i > -L its force is -(k_i / L) q_i,
so q_i(t) = q_i(0) cos(w_i t) with w_i = sqrt(k_i / (L m)). With n = 130, Mt has 16,900
entries and J 33,800 (Eigen's limit is 16,384 doubles).
"""
from gencoord import Model

model = Model(dim=2)
n = model.option("n", 130, "number of oscillators", minimum=1)
k = model.parameter("k", 50.0, "stiffness of the first spring, force per unit strain (N)")
L = model.parameter("L", 1.0, "spring rest length (m)")
m = model.parameter("m", 1.0, "mass of each bob (kg)")

for i in range(n):
    q = model.coordinate(f"x{i}", f"displacement of bob {i} (m)", initial=0.1 + 0.002 * i)
    anchor = model.fixed_point(f"anchor{i}", [-L, i])
    bob = model.particle(f"bob{i}", mass=m, position=[q, i])
    model.spring(anchor, bob, stiffness=k * (1 + i / n), rest_length=L)
