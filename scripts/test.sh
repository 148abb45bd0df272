#!/usr/bin/env bash
# Sets everything up and runs every test:
#   0. the format and lint checks (scripts/check_style.sh);
# then, through CTest,
#   1. the runtime suites (runtime, deformable, integrators, cross-check, scripted
#      coordinates, atlas, fuzz, the sweep program's exchange between ranks) built with
#      AddressSanitizer and UndefinedBehaviorSanitizer;
#   2. the whole suite in a Release build: the generator's Python tests (independent
#      derivations, golden files of generated/, bad models), the generated models' tests,
#      the models' Python modules (built for Debian's /usr/bin/python3, which has NumPy and
#      SciPy), the viewer page in headless Chromium, gencoord sweep under MPI (Open MPI, HDF5,
#      h5py), and the runtime suites again.
# Usage: scripts/test.sh [build-dir]     (GENCOORD_SKIP_SANITIZERS=1 skips step 1)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
jobs=$(nproc 2>/dev/null || echo 2)
python=$(scripts/setup.sh --python-modules --browser --sweep | tail -n 1)
runtime_suites="runtime|deformable|integrators|crosscheck|scripted|atlas|fuzz|large|sweep_exchange"

echo "== format and lint"
scripts/check_style.sh

if [ "${GENCOORD_SKIP_SANITIZERS:-0}" != 1 ]; then
  echo "== runtime suites under AddressSanitizer + UndefinedBehaviorSanitizer"
  # -O1: quick to compile, fast enough to run, and what the sanitizers' authors recommend
  cmake -S . -B "${build}-sanitize" -DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_CXX_FLAGS_SANITIZE=-O1 \
        -DGENCOORD_SANITIZE=ON -DGENCOORD_BUILD_TESTS=ON \
        -DGENCOORD_PYTHON="$python" -DGENCOORD_BUILD_BENCHMARKS=OFF \
        -DPYTHON_EXECUTABLE=/usr/bin/python3 >/dev/null
  targets=$(cmake --build "${build}-sanitize" --target help | grep -oE \
            'gencoord_(runtime|integrator|crosscheck|scripted|atlas|fuzz|large_model|sweep_exchange)_tests|deformable_(tests|demo|drop)' | sort -u)
  # shellcheck disable=SC2086
  cmake --build "${build}-sanitize" -j "$jobs" --target $targets
  ctest --test-dir "${build}-sanitize" -L "$runtime_suites" --output-on-failure \
        --no-tests=error -j "$jobs"
fi

echo "== every test, Release build"
# tests ON explicitly: scripts/demo.sh configures the same build directory with them off
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DGENCOORD_PYTHON="$python" \
      -DGENCOORD_BUILD_TESTS=ON -DGENCOORD_BUILD_BENCHMARKS=OFF \
      -DPYTHON_EXECUTABLE=/usr/bin/python3
cmake --build "$build" -j "$jobs"
ctest --test-dir "$build" --output-on-failure --no-tests=error -j "$jobs"
