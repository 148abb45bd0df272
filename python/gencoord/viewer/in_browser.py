# SPDX-License-Identifier: BSD-3-Clause
"""A viewer page in headless Chromium: open_viewer() for programs (the browser test, the
benchmark), and a PNG of the page at one time (the README's picture):

    python3 -m gencoord.viewer.in_browser out/double_pendulum.html docs/images/viewer.png \\
        [--time 3.55] [--width 1000 --height 700] [--no-trails]
"""

from __future__ import annotations

import argparse
import os
import sys
import time

from gencoord.viewer.headless import Browser, BrowserError, Page

READY_TIMEOUT_S = 30


def open_viewer(browser: Browser, html: str) -> Page:
    """The page in a new tab, once its viewer is ready (window.gencoordViewer.ready)."""
    page = browser.open(html)
    deadline = time.monotonic() + READY_TIMEOUT_S
    while not page.evaluate("Boolean(window.gencoordViewer && gencoordViewer.ready)"):
        if time.monotonic() > deadline:
            raise BrowserError(f"{html}: the viewer did not get ready in {READY_TIMEOUT_S} s "
                               f"({page.console_errors or 'no console errors'})")
        time.sleep(0.02)
    return page


def screenshot(html: str, png: str, at: float, width: int, height: int,
               trails: bool) -> None:
    with Browser(width=width, height=height) as browser:
        page = open_viewer(browser, html)
        page.evaluate(f"gencoordViewer.setTrails({'true' if trails else 'false'}); "
                      f"gencoordViewer.seek({float(at)!r})")
        if page.console_errors:
            raise BrowserError(f"{html}: {page.console_errors[0]}")
        data = page.screenshot()
    with open(png, "wb") as handle:
        handle.write(data)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("html")
    parser.add_argument("png")
    parser.add_argument("--time", type=float, default=0.0, help="seconds (default 0)")
    parser.add_argument("--width", type=int, default=1000)
    parser.add_argument("--height", type=int, default=700)
    parser.add_argument("--no-trails", dest="trails", action="store_false")
    args = parser.parse_args(argv)
    if not os.path.isfile(args.html):
        print(f"screenshot: error: {args.html}: no such page", file=sys.stderr)
        return 1
    try:
        screenshot(args.html, args.png, args.time, args.width, args.height, args.trails)
    except (BrowserError, OSError) as error:
        print(f"screenshot: error: {error}", file=sys.stderr)
        return 1
    print(args.png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
