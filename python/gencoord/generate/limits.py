# SPDX-License-Identifier: BSD-3-Clause
"""Limits that keep a run from going on silently: a wall-clock limit on running the model
file, and a warning before a generation expected to take minutes or more.

The expected time grows with the number of coordinates. A tree (a chain of particles, a robot)
is derived by its recursions: the n-link chain takes about 10 s of CPU at n = 100 and grows
like n^1.3 up to n = 1000 (docs/performance.md, section 1). Other models are derived as sums
over particles, which grow at least quadratically with nq; 9 s at nq = 50 is the estimate's
scale for them.
"""

from __future__ import annotations

import contextlib
import signal
import threading
from typing import Callable

import sympy as sp

SECONDS_AT_50 = 9.0      # a model that is no tree, at nq = 50: CPU
TREE_SECONDS_AT_100 = 10.0  # a tree at nq = 100 (the n-link chain), CPU
TREE_EXPONENT = 1.3         # the chain's growth from 100 to 1000 links
WARN_SECONDS = 180.0     # expected generation time that earns a warning
HANG_GRACE = 5.0         # seconds a body may take to stop once its time is up
NODE_LIMIT = 200_000     # expression nodes in the positions beyond which a warning is due


class LoadTimeout(BaseException):
    """Raised inside the model file at the limit; a BaseException, so that the model's own
    `except Exception` cannot swallow it."""


@contextlib.contextmanager
def wall_clock_limit(seconds: float | None, on_hang: Callable[[], None] | None = None):
    """Raises LoadTimeout inside the body after `seconds` (None or 0: no limit; where
    signals cannot be used, not the main thread, the body runs to its end). A body that
    ignores the signal (it replaced the handler, or catches BaseException) is still running
    HANG_GRACE seconds later: then `on_hang` is called from another thread, to end the
    process with a message."""
    if not (seconds and hasattr(signal, "setitimer")
            and threading.current_thread() is threading.main_thread()):
        yield
        return

    def expire(signum, frame):
        raise LoadTimeout()

    finished, patience = threading.Event(), seconds + HANG_GRACE

    def watch() -> None:
        if not finished.wait(patience) and on_hang is not None:
            on_hang()

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    threading.Thread(target=watch, daemon=True, name="gencoord-load-watchdog").start()
    try:
        yield
    finally:
        finished.set()
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def _nodes_at_least(expressions, limit: int) -> int:
    """The number of expression nodes, counted up to `limit`."""
    count = 0
    for expr in expressions:
        for _ in sp.preorder_traversal(expr):
            count += 1
            if count >= limit:
                return count
    return count


def _duration(seconds: float) -> str:
    for unit, size in (("days", 86400), ("hours", 3600), ("minutes", 60)):
        if seconds >= 2 * size:
            return f"{seconds / size:.0f} {unit}"
    return f"{seconds:.0f} s"


def size_warning(model, tree: bool = False) -> str | None:
    """A warning when generating `model` (a `tree`, or not) is expected to take minutes or
    more, else None."""
    if tree:
        expected = TREE_SECONDS_AT_100 * (model.nq / 100) ** TREE_EXPONENT
        basis = (f"a tree of 100 coordinates takes about {TREE_SECONDS_AT_100:.0f} s, and the "
                 f"time grows like nq^{TREE_EXPONENT}")
    else:
        expected = SECONDS_AT_50 * (model.nq / 50) ** 2
        basis = (f"a model of 50 coordinates that is no tree takes about {SECONDS_AT_50:.0f} "
                 "s, and the time grows at least like nq^2")
    if expected > WARN_SECONDS:
        return (f"{model.nq} coordinates: generation is expected to take about "
                f"{_duration(expected)} ({basis}); interrupt with Ctrl-C if that is not "
                "what you meant")
    if tree:  # a chain's positions hold n^2 terms in all, which its recursions never expand
        return None
    nodes = _nodes_at_least((p.position for p in model.particles), NODE_LIMIT)
    if nodes >= NODE_LIMIT:
        return (f"the particle positions have more than {NODE_LIMIT} expression nodes: "
                "generation may take many minutes; interrupt with Ctrl-C if that is not what "
                "you meant")
    return None
