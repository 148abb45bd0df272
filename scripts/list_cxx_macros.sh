#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Prints the object- and function-like macros a translation unit that includes a generated
# header can see (the header's own includes, the common C library headers, GCC's predefined
# names in the GNU dialect CMake uses by default), one per line: the names
# python/gencoord/cxx/cxx_macros.txt lists, which no model name may take. Only names a model could
# use are printed (a letter first, no "__"); EIGEN_* are refused by their prefix.
# Usage: scripts/list_cxx_macros.sh [compiler]
set -euo pipefail
compiler="${1:-g++}"
eigen="${EIGEN_INCLUDE_DIR:-/usr/include/eigen3}"
printf '#include <%s>\n' array cmath limits string_view tuple Eigen/Cholesky Eigen/Core \
  cassert cerrno cfloat climits csignal cstddef cstdint cstdio cstdlib cstring ctime |
  "$compiler" -std=gnu++17 -I"$eigen" -dM -E -x c++ - |
  awk '$1 == "#define" { sub(/\(.*/, "", $2); print $2 }' |
  grep -E '^[A-Za-z][A-Za-z0-9_]*$' | grep -v -e '__' -e '^EIGEN_' | LC_ALL=C sort -u
