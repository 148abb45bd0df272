# SPDX-License-Identifier: BSD-3-Clause
"""gencoord/viewer: headless Chromium over the DevTools pipe draws with WebGL2, evaluates, takes
screenshots and gathers console errors; the PNG reader undoes every filter. The browser tests
need Chromium (scripts/setup.sh --browser); GENCOORD_SKIP_BROWSER=1 skips them."""

from __future__ import annotations

import os
import random
import shutil
import struct
import sys
import tempfile
import unittest
import zlib
from pathlib import Path
from unittest import mock

from gencoord.viewer.headless import Browser, BrowserError, JavaScriptError, find_chromium
from gencoord.viewer.png import read_png

WIDTH, HEIGHT = 320, 240
CLEAR = (51, 102, 153)  # the clear colour, 0.2 0.4 0.6
RED = (255, 0, 0)
# The red square covers clip coordinates [-0.5, 0] x [0, 0.5]: pixels 80..159 across and, with
# y down as in the screenshot, 60..119.
INSIDE, OUTSIDE, BELOW = (120, 90), (240, 180), (120, 180)

# WebGL2 with nothing but the browser: clear, then a red square drawn by a shader. The URL's
# fragment asks for trouble: #error logs a console error, throws and loads a missing image.
PAGE = """<!doctype html>
<html><head><meta charset="utf-8"><style>body { margin: 0 } canvas { display: block }</style>
</head><body><canvas width="%d" height="%d"></canvas><script>
const gl = document.querySelector("canvas").getContext("webgl2");
function shader(kind, source) {
  const s = gl.createShader(kind);
  gl.shaderSource(s, "#version 300 es\\nprecision highp float;\\n" + source);
  gl.compileShader(s);
  return s;
}
const program = gl.createProgram();
gl.attachShader(program, shader(gl.VERTEX_SHADER,
  "in vec2 p; void main() { gl_Position = vec4(p, 0.0, 1.0); }"));
gl.attachShader(program, shader(gl.FRAGMENT_SHADER,
  "out vec4 colour; void main() { colour = vec4(1.0, 0.0, 0.0, 1.0); }"));
gl.linkProgram(program);
gl.useProgram(program);
gl.bindBuffer(gl.ARRAY_BUFFER, gl.createBuffer());
gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(
  [-0.5, 0, 0, 0, 0, 0.5, -0.5, 0, 0, 0.5, -0.5, 0.5]), gl.STATIC_DRAW);
const p = gl.getAttribLocation(program, "p");
gl.enableVertexAttribArray(p);
gl.vertexAttribPointer(p, 2, gl.FLOAT, false, 0, 0);
gl.clearColor(0.2, 0.4, 0.6, 1.0);
gl.clear(gl.COLOR_BUFFER_BIT);
gl.drawArrays(gl.TRIANGLES, 0, 6);
window.result = {
  webgl2: gl instanceof WebGL2RenderingContext,
  linked: gl.getProgramParameter(program, gl.LINK_STATUS),
  glError: gl.getError(),
  answer: 42,
  words: ["three", "js"],
};
if (location.hash === "#error") {
  console.error("asked for an error", 7);
  const image = document.createElement("img");
  image.src = "missing.png";
  document.body.append(image);
  setTimeout(() => { throw new Error("thrown on purpose"); });
}
</script></body></html>
""" % (WIDTH, HEIGHT)


def assert_colour(test: unittest.TestCase, actual, expected, what: str) -> None:
    test.assertTrue(all(abs(a - e) <= 3 for a, e in zip(actual, expected)),
                    f"{what}: {actual}, expected {expected}")


class BrowserTestCase(unittest.TestCase):
    """Skips with GENCOORD_SKIP_BROWSER=1; fails, saying what to run, without Chromium."""

    @classmethod
    def setUpClass(cls):
        if os.environ.get("GENCOORD_SKIP_BROWSER") == "1":
            raise unittest.SkipTest("GENCOORD_SKIP_BROWSER=1")
        if find_chromium() is None:
            raise AssertionError("no Chromium: run scripts/setup.sh --browser to install it (or "
                                 "set GENCOORD_SKIP_BROWSER=1 to skip the browser tests)")
        cls.folder = Path(tempfile.mkdtemp(prefix="gencoord-headless-test-"))
        cls.addClassCleanup(shutil.rmtree, cls.folder)
        cls.page_path = cls.folder / "page.html"
        cls.page_path.write_text(PAGE, encoding="utf-8")


class HeadlessTest(BrowserTestCase):

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.browser = Browser(WIDTH, HEIGHT, timeout=60)
        cls.addClassCleanup(cls.browser.close)
        cls.page = cls.browser.open(cls.page_path)

    def test_evaluate_returns_json_values(self):
        result = self.page.evaluate("window.result")
        self.assertEqual(result["answer"], 42)
        self.assertEqual(result["words"], ["three", "js"])
        self.assertIsNone(self.page.evaluate("undefined"))
        self.assertEqual(self.page.evaluate("-1 / 0"), float("-inf"))
        self.assertEqual(self.page.evaluate(
            "new Promise(done => setTimeout(() => done('later'), 10))", await_promise=True),
            "later")

    def test_webgl2_draws(self):
        result = self.page.evaluate("window.result")
        self.assertTrue(result["webgl2"], "no WebGL2 context")
        self.assertTrue(result["linked"], "the shaders did not link")
        self.assertEqual(result["glError"], 0)

    def test_screenshot_shows_the_square(self):
        width, height, channels, rows = read_png(self.page.screenshot())
        self.assertEqual((width, height), (WIDTH, HEIGHT))

        def pixel(x, y):
            return tuple(rows[y][x * channels:x * channels + 3])

        assert_colour(self, pixel(*INSIDE), RED, "inside the square")
        assert_colour(self, pixel(*OUTSIDE), CLEAR, "outside the square")
        assert_colour(self, pixel(*BELOW), CLEAR, "below the square")

    def test_a_clean_page_has_no_errors(self):
        self.assertEqual(self.page.console_errors, [])

    def test_console_errors_exceptions_and_failed_loads_are_gathered(self):
        page = self.browser.open(self.page_path.as_uri() + "#error")
        self.addCleanup(page.close)
        # the exception is thrown from a timer, after the load event
        page.evaluate("new Promise(done => setTimeout(done, 50))", await_promise=True)
        errors = "\n".join(page.console_errors)
        self.assertIn("asked for an error 7", errors)
        self.assertIn("Uncaught Error: thrown on purpose", errors)
        self.assertIn("missing.png", errors)
        page.evaluate("console.error('from evaluate'); console.warn('only a warning')")
        self.assertIn("from evaluate", page.console_errors[-1])
        self.assertIn(("warning", "only a warning"), page.messages)

    def test_a_throwing_expression_raises_its_message(self):
        with self.assertRaisesRegex(JavaScriptError, r"Uncaught Error: no such luck\n\s+at "):
            self.page.evaluate("throw new Error('no such luck')")
        with self.assertRaisesRegex(JavaScriptError, "Cannot read properties of null"):
            self.page.evaluate("null.x")
        with self.assertRaisesRegex(JavaScriptError, r"Uncaught \(in promise\) RangeError: no"):
            self.page.evaluate("Promise.reject(new RangeError('no'))", await_promise=True)
        self.assertEqual(self.page.evaluate("window.result.answer"), 42)

    def test_a_missing_file_is_refused(self):
        def tabs():
            return {target["targetId"] for target
                    in self.browser.call("Target.getTargets")["targetInfos"]}

        before = tabs()
        with self.assertRaisesRegex(BrowserError, "ERR_FILE_NOT_FOUND"):
            self.browser.open(self.folder / "no_such_page.html")
        self.assertEqual(tabs(), before, "the failed tab is left open")


class LifetimeTest(BrowserTestCase):
    """A hung page times out, a dead browser is reported, and either way nothing is left."""

    def assert_gone(self, browser: Browser, pid: int) -> None:
        self.assertFalse(os.path.exists(browser._scratch), "the profile is left")
        with self.assertRaises(ProcessLookupError):
            os.kill(pid, 0)

    def test_a_hung_page_times_out_and_the_browser_still_closes(self):
        with self.assertRaisesRegex(BrowserError, "timed out after 1 s waiting for Chromium "
                                    "to answer Runtime.evaluate"):
            with Browser(WIDTH, HEIGHT) as browser:
                pid = browser._process.pid
                browser.open(self.page_path).evaluate("for (;;) {}", timeout=1)
        self.assert_gone(browser, pid)

    def test_a_dead_browser_is_reported(self):
        with Browser(WIDTH, HEIGHT) as browser:
            pid = browser._process.pid
            page = browser.open(self.page_path)
            os.kill(pid, 9)
            with self.assertRaisesRegex(BrowserError, r"closed its pipe \(exit status -9\)"):
                page.evaluate("1")
        self.assert_gone(browser, pid)


class FindChromiumTest(unittest.TestCase):

    def test_the_variable_chooses(self):
        with mock.patch.dict(os.environ, {"GENCOORD_CHROMIUM": sys.executable}):
            self.assertEqual(find_chromium(), shutil.which(sys.executable))
        with mock.patch.dict(os.environ, {"GENCOORD_CHROMIUM": "/no/such/chromium"}):
            self.assertIsNone(find_chromium())


def filtered(kind: int, row: bytes, above: bytes, left: int) -> bytes:
    """The PNG filter `kind` applied to `row`, as an encoder does."""
    out = bytearray()
    for i, x in enumerate(row):
        a = row[i - left] if i >= left else 0
        b = above[i]
        c = above[i - left] if i >= left else 0
        p = a + b - c
        paeth = min((abs(p - a), 0, a), (abs(p - b), 1, b), (abs(p - c), 2, c))[2]
        out.append((x - (0, a, b, (a + b) // 2, paeth)[kind]) & 255)
    return bytes(out)


def png_file(width: int, channels: int, rows: list[bytes], filters: list[int]) -> bytes:
    """A PNG of `rows`, each written with its filter; the data split over two IDAT chunks."""
    def chunk(kind: bytes, body: bytes) -> bytes:
        return (struct.pack(">I", len(body)) + kind + body
                + struct.pack(">I", zlib.crc32(kind + body)))

    data, above = bytearray(), bytes(width * channels)
    for row, kind in zip(rows, filters):
        data += bytes([kind]) + filtered(kind, row, above, channels)
        above = row
    compressed = zlib.compress(bytes(data))
    half = len(compressed) // 2
    colour = {3: 2, 4: 6}[channels]
    return (b"\x89PNG\r\n\x1a\n"
            + chunk(b"IHDR", struct.pack(">IIBBBBB", width, len(rows), 8, colour, 0, 0, 0))
            + chunk(b"IDAT", compressed[:half]) + chunk(b"IDAT", compressed[half:])
            + chunk(b"IEND", b""))


class ReadPngTest(unittest.TestCase):

    def test_every_filter_in_rgb_and_rgba(self):
        generator = random.Random(7)
        filters = [0, 1, 2, 3, 4, 4, 3, 2, 1, 0]
        for channels in (3, 4):
            with self.subTest(channels=channels):
                width = 5
                rows = [bytes(generator.randrange(256) for _ in range(width * channels))
                        for _ in filters]
                self.assertEqual(read_png(png_file(width, channels, rows, filters)),
                                 (width, len(rows), channels, rows))

    def test_damage_is_refused(self):
        good = png_file(2, 3, [bytes(6), bytes(6)], [1, 4])
        self.assertEqual(read_png(good)[3], [bytes(6), bytes(6)])
        with self.assertRaisesRegex(ValueError, "not a PNG"):
            read_png(b"GIF89a" + good[6:])
        broken = bytearray(good)
        broken[20] ^= 1  # inside IHDR
        with self.assertRaisesRegex(ValueError, "damaged IHDR"):
            read_png(bytes(broken))


if __name__ == "__main__":
    unittest.main()
