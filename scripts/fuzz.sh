#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Fuzzes the readers of outside input that are C++ with libFuzzer, under AddressSanitizer and
# UndefinedBehaviorSanitizer (any report stops the run): the mesh readers (Gmsh, TetGen and
# Triangle, Wavefront .obj; tests/fuzz/mesh_reader_fuzzer.cc) and the sweep program's sample
# table (tests/fuzz/sweep_table_fuzzer.cc), from the seeds in tests/fuzz/mesh_corpus and
# table_corpus. Needs clang and libFuzzer (Debian: clang, libclang-rt-14-dev;
# scripts/setup.sh --fuzz). The corpora grow in BUILD/*_corpus, not in the checkout.
#   scripts/fuzz.sh [SECONDS [BUILD]]    SECONDS of fuzzing for each target, the two side by
#                                        side, one per core (default 40); BUILD: build-fuzz
# GENCOORD_FUZZ_SEED (default 1) seeds libFuzzer, so that a run is repeatable; give another to
# explore elsewhere.
# A finding leaves its input in BUILD (crash-*, leak-*, timeout-*) and exits non-zero; rerun
# one with BUILD/mesh_reader_fuzzer FILE (or sweep_table_fuzzer).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
seconds=${1:-40}
build=${2:-build-fuzz}
clang=${CXX_FUZZ:-clang++}
flags=(-std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all)
mkdir -p "$build/mesh_corpus" "$build/table_corpus"
cp -n tests/fuzz/mesh_corpus/* "$build/mesh_corpus/"
cp -n tests/fuzz/table_corpus/* "$build/table_corpus/"
# each target with the readers it uses, compiled in: one program each, no CMake build; the
# small table target compiles beside the mesh target, on the other core
"$clang" "${flags[@]}" -I drivers tests/fuzz/sweep_table_fuzzer.cc -o "$build/sweep_table_fuzzer" &
table_build=$!
"$clang" "${flags[@]}" -I deformable/include -I /usr/include/eigen3 \
  tests/fuzz/mesh_reader_fuzzer.cc deformable/src/mesh_read_gmsh.cpp \
  deformable/src/mesh_read_tetgen.cpp deformable/src/mesh_read_obj.cpp \
  deformable/src/mesh_read_text.cpp deformable/src/mesh.cpp deformable/src/tetrahedralize.cpp \
  deformable/src/closed_surface.cpp deformable/src/run_program.cpp deformable/src/simplex_shape.cpp \
  -o "$build/mesh_reader_fuzzer"
wait "$table_build"
cd "$build"
common=(-max_len=4096 -timeout=10 -rss_limit_mb=2048 -max_total_time="$seconds"
        -seed="${GENCOORD_FUZZ_SEED:-1}" -print_final_stats=1)
# the table beside the mesh readers, each on its own core; its output follows theirs
./sweep_table_fuzzer -dict="$root/tests/fuzz/table.dict" "${common[@]}" table_corpus \
  > sweep_table_fuzzer.log 2>&1 &
table_fuzz=$!
mesh_status=0
./mesh_reader_fuzzer -dict="$root/tests/fuzz/mesh.dict" "${common[@]}" mesh_corpus \
  || mesh_status=$?
table_status=0
wait "$table_fuzz" || table_status=$?
cat sweep_table_fuzzer.log
[ "$mesh_status" -eq 0 ] && [ "$table_status" -eq 0 ]
