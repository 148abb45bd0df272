#!/usr/bin/env bash
# Sets everything up and runs every test: the generator's Python tests, the golden check of
# generated/, and the GoogleTest suites of the runtime, the generated models and the
# deformables, through CTest. Usage: scripts/test.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
jobs=$(nproc 2>/dev/null || echo 2)

python=$(scripts/setup.sh | tail -n 1)
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DGENCOORD_PYTHON="$python" \
      -DGENCOORD_BUILD_BENCHMARKS=OFF
cmake --build "$build" -j "$jobs"
ctest --test-dir "$build" --output-on-failure -j "$jobs"
