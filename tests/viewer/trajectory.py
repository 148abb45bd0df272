# SPDX-License-Identifier: BSD-3-Clause
"""The double pendulum's trajectory the viewer tests draw: 10 s at dt = 1e-3 with RK4, as
`gencoord simulate` writes it. CTest passes the one its simulate program wrote
(GENCOORD_VIEWER_CSV); run alone, a test makes one with the gencoord command (cached)."""

from __future__ import annotations

import functools
import json
import os
import subprocess
import sys
import tempfile

REPOSITORY = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(REPOSITORY, "generated", "double_pendulum.scene.json")


@functools.lru_cache(maxsize=None)
def double_pendulum_csv() -> str:
    given = os.environ.get("GENCOORD_VIEWER_CSV")
    if given:
        return given
    folder = tempfile.mkdtemp(prefix="gencoord-viewer-")
    subprocess.run([sys.executable, os.path.join(REPOSITORY, "gencoord"), "simulate",
                    os.path.join(REPOSITORY, "models", "double_pendulum.py"), "-o", folder,
                    "--dt", "1e-3", "--duration", "10"], check=True, stdout=subprocess.DEVNULL)
    return os.path.join(folder, "double_pendulum.csv")


def double_pendulum_scene() -> dict:
    with open(SCENE, encoding="utf-8") as handle:
        return json.load(handle)
