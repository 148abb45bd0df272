#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The main job, from a fresh clone: set up, then simulate a model and cross-check it against
# the maximal-coordinate penalty model, through the gencoord command.
#   scripts/demo.sh [model] [integrator] [duration]     (default: double_pendulum rk4 10)
# `model` is a name in models/ (double_pendulum, heavy_top, iiwa14: a .py or .urdf file there)
# or the path of any model file or URDF.
# `gencoord simulate` generates the model, compiles a program for it once (cached per user),
# and writes out/<model>.csv (t, q, v, energy, positions) and out/<model>.svg (paths and
# energy error); `gencoord crosscheck` writes out/<model>_crosscheck.csv and .svg (error
# against the penalty stiffness kappa).
set -euo pipefail
cd "$(dirname "$0")/.."
model=${1:-double_pendulum}
integrator=${2:-rk4}
duration=${3:-10}

if [[ -f "$model" ]]; then
  file=$model
elif [[ -f "models/${model}.py" ]]; then
  file="models/${model}.py"
elif [[ -f "models/${model}.urdf" ]]; then
  file="models/${model}.urdf"
else
  echo "demo.sh: no model '${model}': give a name in models/ or the path of a model file" >&2
  exit 2
fi

python=$(scripts/setup.sh | tail -n 1)
echo "== gencoord simulate ${file}"
"$python" ./gencoord simulate "$file" --integrator "$integrator" --dt 1e-3 \
  --duration "$duration"
# A robot's point masses on short rods make its penalty model stiff and slow, and below
# kappa = 1e5 it strays too far to map back to q: a short run over the stiff end instead.
crosscheck=(--kappa 1e2:1e8 --t 5)
[[ "$file" == *.urdf ]] && crosscheck=(--kappa 1e5:1e7 --points 3 --t 0.5)
echo "== gencoord crosscheck ${file}: the penalty model approaches the reduced one"
"$python" ./gencoord crosscheck "$file" "${crosscheck[@]}"
