#!/usr/bin/env bash
# The main job, from a fresh clone: set up, then simulate a model and cross-check it against
# the maximal-coordinate penalty model, through the gencoord command.
#   scripts/demo.sh [model] [integrator] [duration]     (default: double_pendulum rk4 10)
# `gencoord simulate` generates the model, compiles a program for it once (cached per user),
# and writes out/<model>.csv (t, q, v, energy, positions) and out/<model>.svg (paths and
# energy error); `gencoord crosscheck` writes out/<model>_crosscheck.csv and .svg (error
# against the penalty stiffness kappa).
set -euo pipefail
cd "$(dirname "$0")/.."
model=${1:-double_pendulum}
integrator=${2:-rk4}
duration=${3:-10}

python=$(scripts/setup.sh | tail -n 1)
echo "== gencoord simulate models/${model}.py"
"$python" ./gencoord simulate "models/${model}.py" --integrator "$integrator" --dt 1e-3 \
  --duration "$duration"
echo "== gencoord crosscheck models/${model}.py: the penalty model approaches the reduced one"
"$python" ./gencoord crosscheck "models/${model}.py" --kappa 1e2:1e8 --t 5
