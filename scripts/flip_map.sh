#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The double pendulum's time-to-flip map from a fresh clone: installs what is missing (MPI,
# HDF5, h5py, Matplotlib), runs examples/sweeps/double_pendulum_flip.toml on N ranks
# (default 2) and draws out/double_pendulum_flip.png from out/double_pendulum_flip.h5.
#   scripts/flip_map.sh [--ranks N] [--resume | --overwrite]    (docs/sweep.md)
# A run that was stopped (Ctrl-C, a dead rank, a reboot) continues with --resume.
set -euo pipefail
cd "$(dirname "$0")/.."
python=$(scripts/setup.sh --sweep | tail -n 1)
ranks=2
options=()
while [ $# -gt 0 ]; do
  case $1 in
    --ranks) ranks=$2; shift 2 ;;
    --resume|--overwrite) options+=("$1"); shift ;;
    *) echo "flip_map.sh: unknown option $1 (see the comment at its top)" >&2; exit 2 ;;
  esac
done
"$python" ./gencoord sweep examples/sweeps/double_pendulum_flip.toml --ranks "$ranks" \
  "${options[@]}"
/usr/bin/python3 examples/sweeps/flip_map.py out/double_pendulum_flip.h5 \
  out/double_pendulum_flip.png
