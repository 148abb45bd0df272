#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""How long a new user waits for a first result, from a fresh clone with the packages installed.

    python3 bench/first_use.py [--keep DIR]

Clones the repository's committed HEAD into a scratch folder and, with an empty gencoord
cache and ccache switched off (a new user has neither), measures in order:

  1. scripts/demo.sh (simulate and cross-check the double pendulum): wall time;
  2. the first `gencoord simulate` of a 4-coordinate model of the user's own (a triple
     pendulum on a cart, written by this script outside the clone): CPU time;
  3. the first `gencoord python` of that model: CPU time;
  4. the first `gencoord simulate` of the 7-joint arm (models/iiwa14.urdf): CPU time;
  5. whether a second model's first build compiled any runtime source (its build log).

CPU time is user + system of every process the step ran (getrusage of the children), so it
does not depend on the cores; wall time does. Prints each figure beside its target.
"""

from __future__ import annotations

import argparse
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time

REPOSITORY = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# A model of the user's own: a cart with a triple pendulum, 4 coordinates.
USER_MODEL = '''\
"""A cart on a rail carrying a triple pendulum: 4 coordinates."""
from gencoord import Model, cos, sin

model = Model(dim=2)
s = model.coordinate("s", "cart position (m)")
angles = [model.coordinate(f"theta{i}", f"angle of rod {i} from the downward vertical (rad)",
                           initial=0.3 * i) for i in (1, 2, 3)]
g = model.parameter("g", 9.81, "gravitational acceleration (m/s^2)")
cart = model.particle("cart", mass=model.parameter("M", 2.0, "cart mass (kg)"), position=[s, 0])
x, y = s, 0
for i, theta in enumerate(angles, start=1):
    length = model.parameter(f"l{i}", 0.5, f"rod {i} length (m)")
    x, y = x + length * sin(theta), y - length * cos(theta)
    model.particle(f"bob{i}", mass=model.parameter(f"m{i}", 1.0, f"bob {i} mass (kg)"),
                   position=[x, y])
model.gravity([0, -g])
'''


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def measured(command: list[str], cwd: str, env: dict[str, str]) -> tuple[float, float, str]:
    """(wall s, CPU s, stderr) of a command, which must succeed."""
    cpu, wall = _children_cpu(), time.perf_counter()
    result = subprocess.run(command, cwd=cwd, env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True, check=False)
    wall, cpu = time.perf_counter() - wall, _children_cpu() - cpu
    if result.returncode != 0:
        sys.exit(f"first_use: {' '.join(command)} failed:\n{result.stderr}")
    return wall, cpu, result.stderr


def _row(what: str, figure: float, unit: str, target: float) -> str:
    verdict = "ok" if figure < target else "OVER"
    return f"{what:<52} {figure:7.1f} s {unit:<4} (target < {target:g} s: {verdict})"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--keep", help="work in this folder and keep it (default: a scratch "
                                       "folder, removed)")
    args = parser.parse_args()
    scratch = args.keep or tempfile.mkdtemp(prefix="gencoord-first-use-")
    try:
        clone = os.path.join(scratch, "gencoord")
        shutil.rmtree(clone, ignore_errors=True)
        subprocess.run(["git", "clone", "-q", REPOSITORY, clone], check=True)
        cache = os.path.join(scratch, "cache")
        shutil.rmtree(cache, ignore_errors=True)
        env = dict(os.environ, GENCOORD_CACHE_DIR=cache, CCACHE_DISABLE="1")
        user = os.path.join(scratch, "user")
        os.makedirs(user, exist_ok=True)
        model = os.path.join(user, "cart_triple_pendulum.py")
        with open(model, "w", encoding="utf-8") as handle:
            handle.write(USER_MODEL)
        gencoord = [sys.executable, os.path.join(clone, "gencoord")]

        rows = []
        wall, _, _ = measured([os.path.join(clone, "scripts", "demo.sh")], clone, env)
        rows.append(_row("scripts/demo.sh", wall, "wall", 60))
        _, cpu, _ = measured([*gencoord, "simulate", model, "--duration", "1"], user, env)
        rows.append(_row("first simulate of a new 4-coordinate model", cpu, "CPU", 30))
        _, cpu, log = measured([*gencoord, "python", model], user, env)
        python = re.search(r"built for (\S+)", log)
        rows.append(_row("first python of it" + (f" ({python.group(1)})" if python else ""),
                         cpu, "CPU", 30))
        _, cpu, _ = measured([*gencoord, "simulate", os.path.join(clone, "models", "iiwa14.urdf"),
                              "--duration", "1"], user, env)
        rows.append(_row("first simulate of the 7-joint arm (iiwa14.urdf)", cpu, "CPU", 60))
        logs = [os.path.join(cache, entry, "build.log") for entry in os.listdir(cache)
                if entry.startswith("iiwa14-")]
        with open(logs[0], encoding="utf-8") as handle:
            recompiled = re.findall(r"runtime/src/\w+\.cpp", handle.read())
        import sympy
        print(f"python {sys.version.split()[0]}, SymPy {sympy.__version__}, "
              f"{os.cpu_count()} cores; fresh clone, empty cache, no ccache")
        print("\n".join(rows))
        print(f"{'the arm, a second model: runtime sources compiled':<52} {len(recompiled):7d}"
              f"          (target 0: {'ok' if not recompiled else 'OVER'})")
    finally:
        if not args.keep:
            shutil.rmtree(scratch, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
