#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# gencoord vs its peers on the planar n-link chain, as one markdown table: ns per qddot (ours,
# the SymPy-only pipeline, MuJoCo's mj_forward), ns per RK4 step, generation and -O2 compile
# times, then batched qddot and RK4 on 1 and 2 threads.
#
#   scripts/bench_peers.sh [--O2] [--sizes "1;2;5;10;20"] [extra Google Benchmark flags]
#
# On a busy machine add --benchmark_repetitions=5: the table takes the fastest repetition.
#
# --O2 compiles the benchmark at -O2 (the comparison docs/performance.md reports) instead of
# Release's -O3.
# Installs libmujoco-dev when missing; without it the MuJoCo column stays empty.
# Environment: GENCOORD_PEERS_BUILD_DIR (default build-bench-peers), JOBS (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."

o2=OFF
sizes="1;2;5;10;20"
while [ $# -gt 0 ]; do
  case "$1" in
    --O2) o2=ON; shift ;;
    --sizes) sizes="$2"; shift 2 ;;
    *) break ;;
  esac
done

python=$(scripts/setup.sh | tail -n 1)
if [ ! -f /usr/include/mujoco/mujoco.h ]; then
  scripts/install_packages.sh bench_peers libmujoco-dev \
    || echo "bench_peers: no MuJoCo; its column stays empty" >&2
fi

build=${GENCOORD_PEERS_BUILD_DIR:-build-bench-peers}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DGENCOORD_PYTHON="$python" \
      -DGENCOORD_BUILD_TESTS=OFF -DGENCOORD_BUILD_BENCHMARKS=ON \
      -DGENCOORD_PEER_CHAIN_SIZES="$sizes" \
      -DGENCOORD_PEERS_O2="$o2" >/dev/null
cmake --build "$build" -j "${JOBS:-2}" --target bench_peers
# cross-check lines (stderr) are kept for the summary
"$build/bench/bench_peers" --benchmark_min_time=0.2 --benchmark_out="$build/peers.json" \
    --benchmark_out_format=json "$@" 2> >(tee "$build/peers_checks.txt" >&2)
PYTHONHASHSEED=0 "$python" bench/peers/peers_table.py --json "$build/peers.json" \
    --sizes "$sizes" --checks "$build/peers_checks.txt"
