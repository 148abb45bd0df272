#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Fuzzes the readers of outside input that are C++ with libFuzzer, under AddressSanitizer and
# UndefinedBehaviorSanitizer (any report stops the run): the mesh readers (Gmsh, TetGen and
# Triangle, Wavefront .obj; tests/fuzz/mesh_reader_fuzzer.cc), from the seeds in
# tests/fuzz/mesh_corpus. Needs clang and libFuzzer (Debian: clang, libclang-rt-14-dev;
# scripts/setup.sh --fuzz). The corpus grows in BUILD/corpus, not in the checkout.
#   scripts/fuzz.sh [SECONDS [BUILD]]    SECONDS of fuzzing (default 60); BUILD: build-fuzz
# GENCOORD_FUZZ_SEED (default 1) seeds libFuzzer, so that a run is repeatable; give another to
# explore elsewhere.
# A finding leaves its input in BUILD (crash-*, leak-*, timeout-*) and exits non-zero; rerun
# one with BUILD/mesh_reader_fuzzer FILE.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
seconds=${1:-60}
build=${2:-build-fuzz}
mkdir -p "$build/corpus"
cp -n tests/fuzz/mesh_corpus/* "$build/corpus/"
clang=${CXX_FUZZ:-clang++}
# the readers and what they use, compiled with the target: one program, no CMake build
"$clang" -std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
  -I deformable/include -I /usr/include/eigen3 \
  tests/fuzz/mesh_reader_fuzzer.cc deformable/src/mesh_read_gmsh.cpp \
  deformable/src/mesh_read_tetgen.cpp deformable/src/mesh_read_obj.cpp \
  deformable/src/mesh_read_text.cpp deformable/src/mesh.cpp deformable/src/tetrahedralize.cpp \
  deformable/src/closed_surface.cpp deformable/src/run_program.cpp deformable/src/simplex_shape.cpp \
  -o "$build/mesh_reader_fuzzer"
cd "$build"
./mesh_reader_fuzzer -max_total_time="$seconds" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
  -dict="$root/tests/fuzz/mesh.dict" -seed="${GENCOORD_FUZZ_SEED:-1}" \
  -print_final_stats=1 corpus
