#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The planar chain's recursive kernels against its dense ones and MuJoCo, at -O2 and pinned to
# one core (bench/recursion_bench.cc): ns per call, minimum and median over rounds, and ratios.
#
#   scripts/bench_recursion.sh [--sizes "1;2;5;10;20;50;100"] [rounds]
#
# Generating and compiling the n = 100 chain twice takes a few minutes of CPU. Sizes above the
# CMake cache option GENCOORD_RECURSION_DENSE_MAX (default 100; set it with cmake -D in the build
# folder) are generated only with --dynamics recursive and have no dense contender.
# Environment: GENCOORD_RECURSION_BUILD_DIR (default build-bench-recursion), JOBS (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."

sizes="1;2;5;10;20;50;100"
if [ "${1:-}" = --sizes ]; then
  sizes="$2"
  shift 2
fi
python=$(scripts/setup.sh | tail -n 1)
build=${GENCOORD_RECURSION_BUILD_DIR:-build-bench-recursion}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DGENCOORD_PYTHON="$python" \
      -DGENCOORD_BUILD_TESTS=OFF -DGENCOORD_BUILD_BENCHMARKS=ON \
      -DGENCOORD_RECURSION_CHAIN_SIZES="$sizes" >/dev/null
cmake --build "$build" -j "${JOBS:-2}" --target bench_recursion
"$build/bench/bench_recursion" "$@"
