#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Sets everything up and runs every test:
#   0. the format and lint checks (scripts/check_style.sh);
# then, through CTest,
#   1. the suites of the code that can have memory errors (GENCOORD_MEMORY_SUITES), built
#      by clang with AddressSanitizer and UndefinedBehaviorSanitizer: the runtime (on
#      hand-written models), the deformables, the maximal model (the cross-check),
#      constraints, the fuzz targets' corpora and the sweep program's exchange between ranks;
#   2. every other suite in a Release build by the default compiler (GCC), which leaves the
#      memory suites to step 1 (and builds them itself when step 1 is skipped): the
#      generator's Python tests, one CTest test per module, with the python that generates
#      and with the python3 on PATH when its SymPy is another version (independent
#      derivations, golden files of generated/ compared byte for byte by the SymPy that wrote
#      them, bad models), the generated models' tests, the models' Python modules (built
#      for Debian's /usr/bin/python3, which has NumPy and SciPy), the viewer page in
#      headless Chromium, gencoord sweep under MPI (Open MPI, HDF5, h5py), the property
#      tests of the input readers (Hypothesis), and the longest deformable runs;
#   3. the C++ readers of outside input (meshes, the sweep program's sample table) under
#      libFuzzer, 40 s for each, side by side (scripts/fuzz.sh).
# Builds use Ninja and ccache where installed (scripts/setup.sh installs both): ccache keeps
# compiled objects in the user's cache (~/.cache/ccache), shared by every checkout of the
# repository, so a second run compiles only what changed. Generated headers and the reference
# values are kept the same way (GENCOORD_GENERATION_CACHE, ~/.cache/gencoord/generation), so
# a second run derives only the models whose inputs or generator changed. Prints each phase's
# wall time and the slowest tests at the end.
# Usage: scripts/test.sh [build-dir]     (GENCOORD_SKIP_SANITIZERS=1 skips step 1)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/phases.sh
phases_report_on_exit "scripts/test.sh"
build=${1:-build}
jobs=$(nproc 2>/dev/null || echo 2)

phase "set-up (scripts/setup.sh)"
python=$(scripts/setup.sh --python-modules --browser --sweep --pip --property-tests --fuzz --dart --ipopt \
         | tail -n 1)
# the generator's tests run with every SymPy at hand: the python3 on PATH too, if it has one
test_pythons=""
if path_python=$(command -v python3) && "$path_python" -c "import sympy, jinja2" 2>/dev/null; then
  test_pythons=$path_python
fi

# ccache shares objects between checkouts when paths are relative to the checkout
export CCACHE_BASEDIR="$PWD"
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# configure BUILD-DIR ARGS...: Ninja for a new build folder where installed (an existing one
# keeps the generator it was made with)
configure() {
  local dir=$1
  shift
  local generator=()
  if [ ! -f "$dir/CMakeCache.txt" ] && command -v ninja >/dev/null 2>&1; then
    generator=(-G Ninja)
  fi
  cmake -S . -B "$dir" "${generator[@]}" "${launcher[@]}" -DGENCOORD_PYTHON="$python" \
        -DGENCOORD_GENERATION_CACHE="${XDG_CACHE_HOME:-$HOME/.cache}/gencoord/generation" \
        -DGENCOORD_BUILD_BENCHMARKS=OFF -DPYTHON_EXECUTABLE=/usr/bin/python3 "$@" >/dev/null
}

phase "format and lint"
scripts/check_style.sh

# the suites of the code that can have memory errors (GENCOORD_MEMORY_SUITES,
# cmake/memory_suites.cmake) run once: under the sanitizers, or in the Release build when those
# are skipped
memory_suites_in_release=ON
if [ "${GENCOORD_SKIP_SANITIZERS:-0}" != 1 ]; then
  phase "build: the suites under AddressSanitizer + UndefinedBehaviorSanitizer"
  # -O1: quick to compile, fast enough to run, and what the sanitizers' authors recommend.
  # clang (installed with the fuzzers) compiles these template-heavy suites in about 60% of
  # GCC's time, and brings a second compiler's warnings; the Release build is the default
  # compiler's, the one users build with.
  compiler=()
  if clang=$(command -v clang++); then
    compiler=(-DCMAKE_CXX_COMPILER="$clang")
    # CMake drops a folder's settings when its compiler changes: one configured with another
    # compiler starts afresh
    if [ -f "${build}-sanitize/CMakeCache.txt" ] \
       && ! grep -q "^CMAKE_CXX_COMPILER:[A-Z]*=$clang\$" "${build}-sanitize/CMakeCache.txt"; then
      rm -rf "${build}-sanitize"
    fi
  fi
  configure "${build}-sanitize" "${compiler[@]}" -DCMAKE_BUILD_TYPE=Sanitize \
            -DCMAKE_CXX_FLAGS_SANITIZE=-O1 -DGENCOORD_SANITIZE=ON -DGENCOORD_BUILD_TESTS=ON \
            -DGENCOORD_MEMORY_SUITES=ON
  cmake --build "${build}-sanitize" -j "$jobs" --target gencoord_memory_suites
  phase "run: the suites under AddressSanitizer + UndefinedBehaviorSanitizer"
  ctest --test-dir "${build}-sanitize" -L "$(cat "${build}-sanitize/memory_suites.labels")" \
        --output-on-failure --no-tests=error -j "$jobs"
  memory_suites_in_release=OFF
fi

phase "fuzz: the mesh and sample-table readers under libFuzzer (scripts/fuzz.sh, 40 s each)"
scripts/fuzz.sh 40 "${build}-fuzz" > "${build}-fuzz.log" 2>&1 \
  || { tail -n 40 "${build}-fuzz.log"; exit 1; }
grep -E '^Done [0-9]+ runs' "${build}-fuzz.log"

phase "build: everything, Release"
# tests ON explicitly: scripts/demo.sh configures the same build directory with them off
configure "$build" -DCMAKE_BUILD_TYPE=Release -DGENCOORD_BUILD_TESTS=ON \
          -DGENCOORD_MEMORY_SUITES="$memory_suites_in_release" -DGENCOORD_TEST_PYTHONS="$test_pythons"
cmake --build "$build" -j "$jobs"
phase "run: every test, Release"
ctest --test-dir "$build" --output-on-failure --no-tests=error -j "$jobs" \
  | tee "$build/ctest-output.log"
slowest_tests "$build/ctest-output.log" 15
if command -v ccache >/dev/null 2>&1; then
  echo "== ccache"
  ccache --show-stats | sed -nE '/hits|misses|cache size/I s/^/  /p'
fi
