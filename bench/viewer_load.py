#!/usr/bin/env python3
"""How fast the viewer page loads and plays in headless Chromium (WebGL on its CPU renderer,
SwiftShader, so a lower bound for a machine with a GPU): the double pendulum for 10 s at
dt = 1e-3, the page `gencoord simulate` writes.

Each round opens the page in a fresh tab and reads the time from the start of navigation to
the viewer being ready (data decoded, scene built, first frame drawn), then plays for a few
seconds and counts the frames drawn. Prints the page's size and the minimum and median over
the rounds:

    python3 bench/viewer_load.py [--rounds 5] [--play-seconds 3] [--csv out/double_pendulum.csv]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time

REPOSITORY = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPOSITORY)

from tests.viewer.trajectory import double_pendulum_csv, double_pendulum_scene  # noqa: E402
from tool.viewer import page  # noqa: E402
from tool.viewer.headless import Browser  # noqa: E402
from tool.viewer.in_browser import open_viewer  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--play-seconds", type=float, default=3.0)
    parser.add_argument("--csv", help="the trajectory (default: simulated with gencoord)")
    args = parser.parse_args()
    if args.csv:
        os.environ["GENCOORD_VIEWER_CSV"] = args.csv
    with tempfile.TemporaryDirectory(prefix="gencoord-viewer-bench-") as folder:
        html = os.path.join(folder, "double_pendulum.html")
        page.write_page(double_pendulum_csv(), double_pendulum_scene(), html, "double_pendulum")
        loads, rates, script_ms = [], [], []
        with Browser(width=1000, height=700) as browser:
            for _ in range(args.rounds):
                tab = open_viewer(browser, html)
                loads.append(tab.evaluate("gencoordViewer.readyAt") / 1000)
                tab.evaluate("gencoordViewer.seek(0); gencoordViewer.resetStats(); "
                             "gencoordViewer.play()")
                time.sleep(args.play_seconds)
                stats = tab.evaluate("gencoordViewer.stats()")
                rates.append(stats["frames"] / (stats["milliseconds"] / 1000))
                script_ms.append(stats["scriptMilliseconds"] / max(stats["frames"], 1))
                if tab.console_errors:
                    raise RuntimeError(f"console errors: {tab.console_errors}")
                tab.close()
        size = os.path.getsize(html)
    print(f"page: {size / 1e6:.2f} MB (10 s at dt = 1e-3, {args.rounds} rounds)")
    print(f"  load to first frame   min {min(loads):.3f} s   median "
          f"{statistics.median(loads):.3f} s")
    print(f"  frames per second     min {min(rates):.1f}     median "
          f"{statistics.median(rates):.1f}   (playing {args.play_seconds:g} s)")
    print(f"  script per frame      min {min(script_ms):.2f} ms  median "
          f"{statistics.median(script_ms):.2f} ms (the rest is the browser's rendering)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
