#!/usr/bin/env bash
# Regenerates every checked-in header in generated/ from models/ (what the golden test checks).
set -euo pipefail
cd "$(dirname "$0")/.."
for model in pendulum pendulum_3d spherical_pendulum double_pendulum bead_on_rotating_hoop \
             cart_pole spring_pendulum kapitza_pendulum falling_cat rigid_body_euler; do
  ./generate --quiet "models/${model}.py"
done
for n in 1 2 3 5 10; do
  ./generate --quiet models/n_link_chain.py --set "n=${n}"
done
for n in 3 10; do
  ./generate --quiet models/stiff_chain.py --set "n=${n}"
done
