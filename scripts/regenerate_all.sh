#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Regenerates every checked-in header in generated/ from models/ (what the golden test checks):
# the models python/gencoord/tool/model_list.py lists: models/*.py and models/variants.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
models="$(python3 python/gencoord/tool/model_list.py --arguments)"
while read -r -a arguments; do
  ./generate --quiet "${arguments[@]}"
done <<< "${models}"
