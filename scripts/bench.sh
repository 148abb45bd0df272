#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds and runs the benchmarks: ns per qddot and per RK4 step for every model, then the
# generation time of every model. Usage: scripts/bench.sh [extra Google Benchmark flags]
set -euo pipefail
cd "$(dirname "$0")/.."
python=$(scripts/setup.sh | tail -n 1)
cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DGENCOORD_PYTHON="$python" \
      -DGENCOORD_BUILD_TESTS=OFF -DGENCOORD_BUILD_BENCHMARKS=ON >/dev/null
cmake --build build-bench -j "$(nproc 2>/dev/null || echo 2)" --target bench_model_kernels
build-bench/bench/bench_model_kernels --benchmark_min_time=0.2 "$@"
PYTHONHASHSEED=0 "$python" bench/generation_time.py
