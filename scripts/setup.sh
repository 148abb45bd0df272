#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs what gencoord needs on a fresh Debian 12 machine, and nothing that is already there:
# a C++17 compiler, CMake, Ninja, ccache, Eigen 3.4, GoogleTest, Google Benchmark, MuJoCo (the
# reference the robot tests and benchmarks compare with), the tetgen program (read_mesh<3> of
# an .obj surface runs it; the deformable tests need it), and a python3 with SymPy and Jinja2.
# Safe to run again. Prints the python it settled on as its last line.
#   GENCOORD_PYTHON=/usr/bin/python3 scripts/setup.sh    generate with Debian's own SymPy
#   scripts/setup.sh --python-modules    also what the models' Python modules need: pybind11,
#                                        Python's headers, NumPy, SciPy and Matplotlib (the
#                                        README's plot) for /usr/bin/python3
#   scripts/setup.sh --browser           also Chromium, which gencoord/viewer/headless.py runs
#                                        headless for the viewer page's browser tests; or
#                                        checks that the browser $GENCOORD_CHROMIUM names is there
#   scripts/setup.sh --sweep             also what gencoord sweep needs: Open MPI (mpirun and
#                                        its C headers), serial HDF5, and h5py and Matplotlib
#                                        for /usr/bin/python3 (the sweep's picture scripts)
#   scripts/setup.sh --pip               also venv and pip for /usr/bin/python3, with which a
#                                        test installs the package (pip install .)
#   scripts/setup.sh --property-tests    also Hypothesis for /usr/bin/python3 (the property
#                                        tests of the input readers, tests/properties)
#   scripts/setup.sh --fuzz              also clang and libFuzzer (scripts/fuzz.sh)
#   scripts/setup.sh --dart              also DART and its URDF loader, the robot tests' second
#                                        reference (tests/robots/dart_reference_test.cc)
#   scripts/setup.sh --ipopt             also IPOPT, which apps/swing_up.cpp optimizes with
# The options combine.
set -euo pipefail

python_modules=false
browser=false
sweep=false
pip=false
property_tests=false
fuzz=false
dart=false
ipopt=false
for option in "$@"; do
  case $option in
    --python-modules) python_modules=true ;;
    --browser) browser=true ;;
    --sweep) sweep=true ;;
    --pip) pip=true ;;
    --property-tests) property_tests=true ;;
    --fuzz) fuzz=true ;;
    --dart) dart=true ;;
    --ipopt) ipopt=true ;;
  esac
done

packages=()
command -v g++ >/dev/null 2>&1 || packages+=(g++)
command -v make >/dev/null 2>&1 || packages+=(make)
command -v cmake >/dev/null 2>&1 || packages+=(cmake)
# Ninja and ccache make every build that follows quicker: the gencoord command's, the tests'
command -v ninja >/dev/null 2>&1 || packages+=(ninja-build)
command -v ccache >/dev/null 2>&1 || packages+=(ccache)
[ -f /usr/include/eigen3/Eigen/Core ] || packages+=(libeigen3-dev)
[ -d /usr/lib/x86_64-linux-gnu/cmake/GTest ] || [ -d /usr/lib/cmake/GTest ] \
  || packages+=(libgtest-dev libgmock-dev)
[ -d /usr/lib/x86_64-linux-gnu/cmake/benchmark ] || [ -d /usr/lib/cmake/benchmark ] \
  || packages+=(libbenchmark-dev)
[ -f /usr/lib/x86_64-linux-gnu/cmake/mujoco/mujocoConfig.cmake ] || packages+=(libmujoco-dev)
# TetGen 1.5 as a program (AGPL, so run and never linked): tetrahedra for closed .obj surfaces
command -v tetgen >/dev/null 2>&1 || packages+=(tetgen)

# The generator needs SymPy and Jinja2: from $GENCOORD_PYTHON when set, else from the python3
# on PATH when it has both, else from Debian's python3-sympy and python3-jinja2.
python=${GENCOORD_PYTHON:-python3}
if ! "$python" -c "import sympy, jinja2" >/dev/null 2>&1; then
  if [ -z "${GENCOORD_PYTHON:-}" ]; then
    python=/usr/bin/python3
  elif [ "$python" != /usr/bin/python3 ]; then
    echo "setup: error: GENCOORD_PYTHON=$python cannot import sympy and jinja2" >&2
    exit 1
  fi
  /usr/bin/python3 -c "import sympy, jinja2" >/dev/null 2>&1 \
    || packages+=(python3 python3-sympy python3-jinja2)
fi

if $python_modules; then
  [ -f /usr/lib/cmake/pybind11/pybind11Config.cmake ] || packages+=(pybind11-dev)
  /usr/bin/python3 -c 'import os, sysconfig
assert os.path.isfile(os.path.join(sysconfig.get_paths()["include"], "Python.h"))' \
    >/dev/null 2>&1 || packages+=(python3-dev)
  /usr/bin/python3 -c "import numpy" >/dev/null 2>&1 || packages+=(python3-numpy)
  /usr/bin/python3 -c "import scipy" >/dev/null 2>&1 || packages+=(python3-scipy)
  /usr/bin/python3 -c "import matplotlib" >/dev/null 2>&1 || packages+=(python3-matplotlib)
fi

# the browser gencoord/viewer/headless.py would run: $GENCOORD_CHROMIUM, else one of these names
if $browser; then
  if [ -n "${GENCOORD_CHROMIUM:-}" ]; then
    if ! command -v "$GENCOORD_CHROMIUM" >/dev/null 2>&1; then
      echo "setup: error: GENCOORD_CHROMIUM=$GENCOORD_CHROMIUM is not a program" >&2
      exit 1
    fi
  elif ! { command -v chromium || command -v chromium-browser || command -v google-chrome
         } >/dev/null 2>&1; then
    packages+=(chromium)
  fi
fi

# gencoord sweep: its driver compiles against MPI and HDF5 and runs under mpirun
if $sweep; then
  command -v mpirun >/dev/null 2>&1 || packages+=(openmpi-bin)
  { command -v mpicxx >/dev/null 2>&1 \
    && [ -f /usr/lib/x86_64-linux-gnu/openmpi/include/mpi.h ]; } || packages+=(libopenmpi-dev)
  [ -f /usr/include/hdf5/serial/hdf5.h ] || packages+=(libhdf5-dev)
  /usr/bin/python3 -c "import h5py" >/dev/null 2>&1 || packages+=(python3-h5py)
  /usr/bin/python3 -c "import matplotlib" >/dev/null 2>&1 || packages+=(python3-matplotlib)
fi

if $pip; then
  /usr/bin/python3 -c "import ensurepip, venv" >/dev/null 2>&1 || packages+=(python3-venv)
  /usr/bin/python3 -m pip --version >/dev/null 2>&1 || packages+=(python3-pip)
fi

if $property_tests; then
  /usr/bin/python3 -c "import hypothesis" >/dev/null 2>&1 || packages+=(python3-hypothesis)
fi

if $fuzz; then
  command -v clang++ >/dev/null 2>&1 || packages+=(clang)
  compgen -G "/usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a" >/dev/null \
    || packages+=(libclang-rt-14-dev)
fi

if $dart; then
  [ -f /usr/share/dart/cmake/DARTConfig.cmake ] || packages+=(libdart-dev)
  [ -f /usr/include/dart/utils/urdf/DartLoader.hpp ] || packages+=(libdart-utils-urdf-dev)
fi

if $ipopt; then
  [ -f /usr/include/coin/IpIpoptApplication.hpp ] || packages+=(coinor-libipopt-dev pkg-config)
fi

"$(dirname "$0")/install_packages.sh" setup "${packages[@]}"
command -v "$python"
