#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""How fast the viewer page loads and plays in headless Chromium (WebGL on its CPU renderer,
SwiftShader, so a lower bound for a machine with a GPU): the double pendulum for 10 s at
dt = 1e-3, the page `gencoord simulate` writes.

Each round opens the page in a fresh tab and reads the time from the start of navigation to
the viewer being ready (data decoded, scene built, first frame drawn), then plays for a few
seconds and counts the frames drawn. Interleaved with it, the same count on an empty page
that only asks for animation frames: the most frames this browser gives any page here, the
ceiling of the viewer's rate. Prints the page's size and the minimum and median over the
rounds:

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
sys.path.insert(0, os.path.join(REPOSITORY, "python"))

from tests.viewer.trajectory import double_pendulum_csv, double_pendulum_scene  # noqa: E402
from gencoord.viewer import page  # noqa: E402
from gencoord.viewer.headless import Browser  # noqa: E402
from gencoord.viewer.in_browser import open_viewer  # noqa: E402


# a page that draws nothing and counts its animation frames, with the viewer's hook for them
EMPTY_PAGE = """<!DOCTYPE html><html><body><script>
let frames = 0, since = performance.now();
(function tick() { frames += 1; requestAnimationFrame(tick); })();
window.gencoordViewer = { ready: true, readyAt: performance.now(), seek() {}, play() {},
  resetStats() { frames = 0; since = performance.now(); },
  stats: () => ({ frames, milliseconds: performance.now() - since, scriptMilliseconds: 0 }) };
</script></body></html>"""


def frame_rate(browser, html: str, seconds: float) -> tuple[float, float, dict]:
    """Opens `html`, plays it for `seconds`: (load time in s, frames per second, stats)."""
    tab = open_viewer(browser, html)
    load = tab.evaluate("gencoordViewer.readyAt") / 1000
    tab.evaluate("gencoordViewer.seek(0); gencoordViewer.resetStats(); gencoordViewer.play()")
    time.sleep(seconds)
    stats = tab.evaluate("gencoordViewer.stats()")
    if tab.console_errors:
        raise RuntimeError(f"console errors: {tab.console_errors}")
    tab.close()
    return load, stats["frames"] / (stats["milliseconds"] / 1000), stats


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
        empty = os.path.join(folder, "empty.html")
        with open(empty, "w", encoding="utf-8") as handle:
            handle.write(EMPTY_PAGE)
        loads, rates, ceilings, script_ms = [], [], [], []
        with Browser(width=1000, height=700) as browser:
            for _ in range(args.rounds):
                load, rate, stats = frame_rate(browser, html, args.play_seconds)
                loads.append(load)
                rates.append(rate)
                script_ms.append(stats["scriptMilliseconds"] / max(stats["frames"], 1))
                ceilings.append(frame_rate(browser, empty, args.play_seconds)[1])
        size = os.path.getsize(html)
    print(f"page: {size / 1e6:.2f} MB (10 s at dt = 1e-3, {args.rounds} rounds)")
    print(f"  load to first frame   min {min(loads):.3f} s   median "
          f"{statistics.median(loads):.3f} s")
    print(f"  frames per second     min {min(rates):.1f}     median "
          f"{statistics.median(rates):.1f}   (playing {args.play_seconds:g} s)")
    print(f"  empty page's frames   min {min(ceilings):.1f}     median "
          f"{statistics.median(ceilings):.1f}   (the browser's ceiling here)")
    ratios = [rate / ceiling for rate, ceiling in zip(rates, ceilings)]
    print(f"  viewer / empty page   min {min(ratios):.2f}     median "
          f"{statistics.median(ratios):.2f}")
    print(f"  script per frame      min {min(script_ms):.2f} ms  median "
          f"{statistics.median(script_ms):.2f} ms (the rest is the browser's rendering)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
