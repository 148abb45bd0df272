#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Deformable mass-spring demo, from a fresh clone: set up, build, run one scenario.
#   scripts/deformable_demo.sh [disk-drop|cantilever|brittle-beam|particles] [options...]
# Writes out/<scenario>/frames.csv, springs.csv, frames.svg (see --help for options) and
# frames.html, which plays the run in a browser (docs/viewer.md).
set -euo pipefail
cd "$(dirname "$0")/.."
scenario=${1:-brittle-beam}
shift || true
python=$(scripts/setup.sh | tail -n 1)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DGENCOORD_PYTHON="$python" \
      -DGENCOORD_BUILD_TESTS=OFF -DGENCOORD_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build -j "$(nproc 2>/dev/null || echo 2)" --target deformable_demo
build/deformable/deformable_demo "$scenario" --out "out/${scenario}" "$@"
PYTHONPATH=python "$python" -m gencoord.viewer.deformable "out/${scenario}"
