# SPDX-License-Identifier: BSD-3-Clause
"""Balances inverted poles on a cart with LQR: linearize the model about the upright
equilibrium, design the gain with SciPy's solve_continuous_are, and simulate the nonlinear
model under u = -K x from a 0.2 rad offset of the lower pole.

    /usr/bin/python3 apps/lqr_balance.py [--models cart_pole,double_pendulum_on_cart]
                                         [-o out] [--module-dir DIR]

For each model it builds the Python module with `gencoord python` (or imports it from
--module-dir), writes out/lqr_<model>.csv (t, the coordinates, their rates and u) and
out/lqr_<model>.svg (the states and the force over time), and prints the gain and the
largest state left after 10 s. Exits with status 1 if a pole is not balanced. Needs NumPy and
SciPy (Debian: python3-numpy, python3-scipy).
"""

from __future__ import annotations

import argparse
import csv
import importlib
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))

from gencoord.tool.timeseries_svg import write_timeseries_svg  # noqa: E402

try:
    import numpy as np
    from scipy.linalg import solve_continuous_are
except ImportError as missing:
    sys.exit(f"lqr_balance: needs NumPy and SciPy ({missing}); on Debian run it with "
             "/usr/bin/python3 after `apt-get install python3-numpy python3-scipy`")

OFFSET = 0.2         # initial angle of the lower pole from upright (rad)
DURATION = 10.0      # simulated time (s)
STEP = 1e-3          # RK4 step (s)
BALANCED = 1e-3      # largest |q|, |v| allowed at the end


def load_module(model: str, module_dir: str | None, output_dir: str):
    """The model's Python module, built by `gencoord python` unless module_dir has it."""
    if module_dir is None:
        module_dir = os.path.join(output_dir, "python")
        subprocess.run([os.path.join(ROOT, "gencoord"), "python",
                        os.path.join(ROOT, "models", f"{model}.py"), "-o", module_dir,
                        "--python", sys.executable], check=True, stdout=subprocess.DEVNULL)
    sys.path.insert(0, os.path.abspath(module_dir))
    return importlib.import_module(model)


def lqr_gain(A, B, Q, R):
    """K of the LQR law u = -K x: R^-1 B^T X with X the stabilizing solution of the CARE."""
    X = solve_continuous_are(A, B, Q, R)
    return np.linalg.solve(R, B.T @ X)


def balance(module, output_dir: str) -> float:
    """Designs and simulates the controller; returns the largest |q|, |v| at the end."""
    n = module.nq
    upright = np.zeros(n)
    A, B = module.linearize(upright, upright, u=0.0)
    # weigh the angles more than the cart's position; the force costs 1 per N^2
    Q = np.diag([10.0] + [100.0] * (n - 1) + [1.0] * n)
    K = lqr_gain(A, B, Q, np.eye(1))
    eigenvalues = np.linalg.eigvals(A - B @ K)
    print(f"{module.name}: K = {np.array2string(K[0], precision=3)}, closed-loop "
          f"eigenvalues' largest real part {eigenvalues.real.max():.3f}")

    def law(t, q, v):
        return -K @ np.concatenate([q, v])

    q0 = upright.copy()
    q0[1] = OFFSET
    t, q, v, _ = module.simulate(q0, upright, t_end=DURATION, dt=STEP, inputs=law, every=10)
    u = np.array([law(ti, qi, vi)[0] for ti, qi, vi in zip(t, q, v)])
    names = list(module.coordinate_names)
    rates = [f"{name}_dot" for name in names]
    path = os.path.join(output_dir, f"lqr_{module.name}.csv")
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(["t", *names, *rates, "u"])
        for row in zip(t, *q.T, *v.T, u):
            writer.writerow([repr(float(x)) for x in row])
    svg = os.path.join(output_dir, f"lqr_{module.name}.svg")
    write_timeseries_svg(path, svg, [("Cart (m)", ["s"]), ("Angles (rad)", names[1:]),
                                     ("Rates", rates), ("Force on the cart (N)", ["u"])],
                         title=f"{module.name}: LQR from a {OFFSET} rad offset")
    left = max(np.abs(q[-1]).max(), np.abs(v[-1]).max())
    print(f"  wrote {path} and {svg}; after {DURATION:g} s the largest |q|, |v| is "
          f"{left:.2e}, the largest |u| was {np.abs(u).max():.2f} N")
    return left


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--models", default="cart_pole,double_pendulum_on_cart")
    parser.add_argument("-o", "--output-dir", default="out")
    parser.add_argument("--module-dir", help="import the modules from here instead of "
                        "building them")
    args = parser.parse_args(argv)
    os.makedirs(args.output_dir, exist_ok=True)
    worst = 0.0
    for model in args.models.split(","):
        worst = max(worst, balance(load_module(model, args.module_dir, args.output_dir),
                                   args.output_dir))
    if worst > BALANCED:
        print(f"lqr_balance: not balanced: {worst:.2e} > {BALANCED:g}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
