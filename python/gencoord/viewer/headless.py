# SPDX-License-Identifier: BSD-3-Clause
"""Headless Chromium driven through the DevTools protocol over a pipe, standard library only.

    with Browser(width=800, height=600) as browser:
        page = browser.open("out/viewer.html")
        page.evaluate("document.title")
        png = page.screenshot()
        assert not page.console_errors

Chromium reads NUL-terminated JSON messages from its fd 3 and writes its own to fd 4
(--remote-debugging-pipe). Every wait has a deadline: a hung browser raises BrowserError saying
what was awaited instead of hanging the caller. WebGL runs on SwiftShader, Chromium's CPU
renderer, so no GPU or display is needed.
"""

from __future__ import annotations

import base64
import contextlib
import fcntl
import json
import math
import os
import re
import select
import shutil
import signal
import subprocess
import tempfile
import time
from pathlib import Path

CANDIDATES = ("chromium", "chromium-browser", "google-chrome")

# WebGL on SwiftShader: --enable-unsafe-swiftshader opts in to it (without a GPU Chromium still
# falls back to it unasked, but warns on every page that this fallback is going away), and
# --use-angle=swiftshader chooses it even where there is a GPU, so that pictures and timings
# do not depend on the machine. The rest keep a run quiet, offline and away from the user's
# profile.
FLAGS = (
    "--headless=new",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--no-first-run",
    "--no-default-browser-check",
    "--disable-extensions",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--mute-audio",
    "--hide-scrollbars",
)

# the JavaScript values that JSON cannot carry
UNSERIALIZABLE = {"NaN": math.nan, "Infinity": math.inf, "-Infinity": -math.inf, "-0": -0.0}


class BrowserError(RuntimeError):
    """Chromium failed, refused a command, or did not answer in time."""


class JavaScriptError(BrowserError):
    """An evaluated expression threw; the message is the exception's text."""


def find_chromium() -> str | None:
    """The Chromium to run: $GENCOORD_CHROMIUM, else the first of CANDIDATES on PATH."""
    override = os.environ.get("GENCOORD_CHROMIUM")
    if override:
        return shutil.which(override)
    return next(filter(None, map(shutil.which, CANDIDATES)), None)


class Browser:
    """One headless Chromium with a throw-away profile; a context manager that kills it and
    removes the profile on exit. `timeout` (seconds) bounds every wait that is not given its
    own; `version` is Chromium's, as in "Chrome/120.0.6099.224"."""

    def __init__(self, width: int = 1000, height: int = 700, executable: str | None = None,
                 timeout: float = 30.0):
        self.width, self.height, self.timeout = width, height, timeout
        executable = executable or find_chromium()
        if not executable:
            raise BrowserError("no Chromium found (looked for " + ", ".join(CANDIDATES)
                               + "): run scripts/setup.sh --browser, or set GENCOORD_CHROMIUM")
        self._pages: dict[str, Page] = {}
        self._replies: dict[int, dict] = {}
        self._detached: set[str] = set()
        self._buffer = bytearray()
        self._next_id = 0
        self._process: subprocess.Popen[bytes] | None = None
        self._to_browser: int | None = None
        self._from_browser: int | None = None
        self._scratch = tempfile.mkdtemp(prefix="gencoord-chromium-")
        self._log_path = os.path.join(self._scratch, "stderr.log")
        try:
            self._start(executable)
        except BaseException:
            self.close()
            raise

    def _start(self, executable: str) -> None:
        command = [executable, *FLAGS, f"--window-size={self.width},{self.height}",
                   "--user-data-dir=" + os.path.join(self._scratch, "profile"),
                   "--remote-debugging-pipe", "about:blank"]
        if os.geteuid() == 0:
            command.insert(1, "--no-sandbox")  # Chromium refuses to sandbox itself as root
        # The child's ends go to fds 3 and 4 by dup2, which leaves the copies inheritable. Moved
        # above 4 first, so that neither dup2 can overwrite the other's source.
        to_child, self._to_browser = os.pipe()
        self._from_browser, from_child = os.pipe()
        child_in, child_out = (fcntl.fcntl(fd, fcntl.F_DUPFD_CLOEXEC, 5)
                               for fd in (to_child, from_child))
        os.close(to_child)
        os.close(from_child)
        os.set_blocking(self._to_browser, False)

        def on_fds_3_and_4():
            os.dup2(child_in, 3)
            os.dup2(child_out, 4)

        try:
            with open(self._log_path, "wb") as log:
                # Its own process group: killed as one at exit, and spared the terminal's ^C.
                # Not close_fds, which would close fds 3 and 4: Python opens close-on-exec.
                # Its caches and crash reports go to the scratch folder, not ~/.cache, ~/.config.
                self._process = subprocess.Popen(
                    command, stdin=subprocess.DEVNULL, stdout=log, stderr=log,
                    close_fds=False, preexec_fn=on_fds_3_and_4, start_new_session=True,
                    env=dict(os.environ, XDG_CACHE_HOME=self._scratch,
                             XDG_CONFIG_HOME=self._scratch))
        finally:
            os.close(child_in)
            os.close(child_out)
        self.version = self.call("Browser.getVersion")["product"]

    def open(self, url_or_path: str | os.PathLike, timeout: float | None = None) -> Page:
        """A new tab showing `url_or_path` (a URL, or a file's path), once its load event has
        fired."""
        url = str(url_or_path)
        if isinstance(url_or_path, os.PathLike) or not re.match(r"[A-Za-z][\w+.-]*:", url):
            url = Path(url).resolve().as_uri()
        target = self.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = self.call("Target.attachToTarget",
                            {"targetId": target, "flatten": True})["sessionId"]
        page = self._pages[session] = Page(self, target, session)
        page.call("Emulation.setDeviceMetricsOverride", {
            "width": self.width, "height": self.height, "deviceScaleFactor": 1,
            "mobile": False})
        for domain in ("Runtime", "Page", "Log"):
            page.call(domain + ".enable")
        page.call("Page.setLifecycleEventsEnabled", {"enabled": True})
        try:
            page.navigate(url, timeout)
        except BrowserError:
            with contextlib.suppress(BrowserError):
                page.close(timeout=5)
            raise
        return page

    def call(self, method: str, params: dict | None = None, session: str | None = None,
             timeout: float | None = None) -> dict:
        """Sends one DevTools command, to the browser or to a tab's `session`, and returns its
        result; raises BrowserError on an error reply."""
        self._next_id += 1
        ident = self._next_id
        message = {"id": ident, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        data = json.dumps(message).encode() + b"\0"
        what = f"Chromium to answer {method}"
        timeout = self.timeout if timeout is None else timeout
        deadline = time.monotonic() + timeout
        assert self._to_browser is not None  # open from _start until close
        while data:
            if not select.select([], [self._to_browser], [], _left(deadline))[1]:
                raise BrowserError(f"timed out after {timeout:g} s waiting for {what}")
            try:
                data = data[os.write(self._to_browser, data):]
            except BrokenPipeError:
                raise BrowserError(self._death(what)) from None
        self.wait(lambda: ident in self._replies, what, timeout)
        reply = self._replies.pop(ident)
        if "error" in reply:
            raise BrowserError(f"{method} failed: {reply['error'].get('message')}")
        return reply.get("result", {})

    def wait(self, done, what: str, timeout: float | None = None) -> None:
        """Reads and dispatches Chromium's messages until done() is true; raises BrowserError
        naming `what` after `timeout` seconds."""
        timeout = self.timeout if timeout is None else timeout
        deadline = time.monotonic() + timeout
        assert self._from_browser is not None  # open from _start until close
        while not done():
            if not select.select([self._from_browser], [], [], _left(deadline))[0]:
                raise BrowserError(f"timed out after {timeout:g} s waiting for {what}")
            chunk = os.read(self._from_browser, 1 << 20)
            if not chunk:
                raise BrowserError(self._death(what))
            scanned = len(self._buffer)
            self._buffer += chunk
            while (end := self._buffer.find(b"\0", scanned)) >= 0:
                message = json.loads(self._buffer[:end])
                del self._buffer[:end + 1]
                scanned = 0
                if "id" in message:
                    self._replies[message["id"]] = message
                elif message["method"] == "Target.detachedFromTarget":
                    self._detached.add(message["params"]["sessionId"])
                elif message.get("sessionId") in self._pages:
                    self._pages[message["sessionId"]]._event(message["method"],
                                                             message.get("params", {}))

    def _death(self, what: str) -> str:
        assert self._process is not None  # started before the first call
        code: int | str
        try:
            code = self._process.wait(5)
        except subprocess.TimeoutExpired:
            code = "unknown"
        with open(self._log_path, "rb") as log:
            lines = log.read().decode(errors="replace").strip().splitlines()
        # less the complaints of a machine without a desktop session bus
        tail = [line for line in lines if ":ERROR:dbus/" not in line][-10:]
        return (f"Chromium closed its pipe (exit status {code}) while waiting for {what}; "
                "its last output:\n  " + "\n  ".join(tail))

    def close(self) -> None:
        """Closes Chromium, politely if it answers, then kills whatever of it is left and
        removes its profile. Safe to call twice."""
        if self._process and self._process.poll() is None:
            with contextlib.suppress(BrowserError, subprocess.TimeoutExpired):
                self.call("Browser.close", timeout=5)
                self._process.wait(5)
        if self._process:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(self._process.pid, signal.SIGKILL)  # and the helpers it left
            self._process.wait()
            self._process = None
        for fd in (self._to_browser, self._from_browser):
            if fd is not None:
                os.close(fd)
        self._to_browser = self._from_browser = None
        shutil.rmtree(self._scratch, ignore_errors=True)

    def __enter__(self) -> Browser:
        return self

    def __exit__(self, *exception) -> None:
        self.close()


class Page:
    """One tab. `messages`: (level, text) for every console call, uncaught exception and
    browser log entry so far, gathered as Chromium reports them; the levels are the protocol's
    ("error", "warning", "log", "info", ...)."""

    def __init__(self, browser: Browser, target: str, session: str):
        self.browser, self.target, self.session = browser, target, session
        self.messages: list[tuple[str, str]] = []
        self._loaded: set[str] = set()

    @property
    def console_errors(self) -> list[str]:
        """The console errors, uncaught exceptions and browser log errors so far."""
        return [text for level, text in self.messages if level == "error"]

    def call(self, method: str, params: dict | None = None,
             timeout: float | None = None) -> dict:
        return self.browser.call(method, params, self.session, timeout)

    def navigate(self, url: str, timeout: float | None = None) -> None:
        """Loads `url` and waits for its load event."""
        reply = self.call("Page.navigate", {"url": url}, timeout)
        if "errorText" in reply:
            raise BrowserError(f"cannot load {url}: {reply['errorText']}")
        # the load event of this navigation, not of the blank page before it; a navigation
        # within the document (a new #fragment) has neither
        loader = reply.get("loaderId")
        if loader is None:
            return
        self.browser.wait(lambda: loader in self._loaded, f"the load event of {url}", timeout)

    def evaluate(self, expression: str, await_promise: bool = False,
                 timeout: float | None = None):
        """The value of a JavaScript expression, as JSON gives it (a promise's value with
        `await_promise`; NaN and the infinities as floats, a BigInt as its text); raises
        JavaScriptError with the exception's text if it throws."""
        reply = self.call("Runtime.evaluate", {
            "expression": expression, "returnByValue": True, "awaitPromise": await_promise},
            timeout)
        if "exceptionDetails" in reply:
            raise JavaScriptError(_exception_text(reply["exceptionDetails"]))
        result = reply["result"]
        if "unserializableValue" in result:
            return UNSERIALIZABLE.get(result["unserializableValue"],
                                      result["unserializableValue"])
        return result.get("value")

    def screenshot(self, timeout: float | None = None) -> bytes:
        """The viewport as a PNG, width x height pixels. Brings the tab to the front: one
        hidden behind another draws no frames, and a screenshot waits for one."""
        self.call("Page.bringToFront", timeout=timeout)
        reply = self.call("Page.captureScreenshot", {"format": "png"}, timeout)
        return base64.b64decode(reply["data"])

    def close(self, timeout: float | None = None) -> None:
        """Closes the tab, and waits until it is gone."""
        del self.browser._pages[self.session]
        self.browser.call("Target.closeTarget", {"targetId": self.target}, timeout=timeout)
        self.browser.wait(lambda: self.session in self.browser._detached,
                          "the tab to close", timeout)

    def _event(self, method: str, params: dict) -> None:
        if method == "Page.lifecycleEvent" and params["name"] == "load":
            self._loaded.add(params["loaderId"])
        elif method == "Runtime.consoleAPICalled":
            level = "error" if params["type"] == "assert" else params["type"]
            self.messages.append((level, " ".join(map(_describe, params["args"]))))
        elif method == "Runtime.exceptionThrown":
            self.messages.append(("error", _exception_text(params["exceptionDetails"])))
        elif method == "Log.entryAdded":
            entry = params["entry"]
            where = f" ({entry['url']})" if entry.get("url") else ""
            self.messages.append((entry["level"], entry["text"] + where))


def _describe(value: dict) -> str:
    """A console argument as the console would print it."""
    if "value" in value:
        return str(value["value"])
    return value.get("description") or value.get("unserializableValue") or value["type"]


def _exception_text(details: dict) -> str:
    """'Uncaught Error: message' and the stack: Chromium's summary ('Uncaught', or 'Uncaught
    (in promise) Error: message'), then what was thrown, less what the summary already says."""
    text = details["text"]
    if "exception" not in details:
        return text
    thrown = _describe(details["exception"])
    first = thrown.split("\n")[0]
    return text + thrown[len(first):] if text.endswith(first) else f"{text} {thrown}"


def _left(deadline: float) -> float:
    return max(0.0, deadline - time.monotonic())
