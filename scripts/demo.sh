#!/usr/bin/env bash
# The main job, from a fresh clone: set up, generate a model, build, simulate, cross-check
# against the maximal-coordinate penalty model, and show the results.
#   scripts/demo.sh [model] [integrator] [duration]     (default: double_pendulum rk4 10)
# Writes out/<model>.csv (t, q, v, energy, particle positions), out/<model>.svg (paths and
# energy drift), out/<model>_crosscheck.csv and out/<model>_crosscheck.svg (error vs kappa).
set -euo pipefail
cd "$(dirname "$0")/.."
model=${1:-double_pendulum}
integrator=${2:-rk4}
duration=${3:-10}
build=build
jobs=$(nproc 2>/dev/null || echo 2)

python=$(scripts/setup.sh | tail -n 1)
echo "== generate models/${model}.py"
"$python" ./generate "models/${model}.py" -v
echo "== build"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DGENCOORD_PYTHON="$python" \
      -DGENCOORD_BUILD_TESTS=OFF -DGENCOORD_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j "$jobs" --target simulate crosscheck
echo "== simulate"
mkdir -p out
"$build/apps/simulate" "$model" --integrator "$integrator" --dt 1e-3 --duration "$duration" \
  --output "out/${model}.csv"
"$python" scripts/plot_trajectory.py "out/${model}.csv" "out/${model}.svg"
echo "== cross-check: maximal-coordinate penalty model vs the reduced model as kappa grows"
"$build/apps/crosscheck" "$model" --kappa 1e2:1e8 --t 5 \
  --csv "out/${model}_crosscheck.csv" --svg "out/${model}_crosscheck.svg"
