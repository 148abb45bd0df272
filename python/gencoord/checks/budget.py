# SPDX-License-Identifier: BSD-3-Clause
"""Time budgets of the generation-time checks, in CPU seconds of this process.

CPU time rather than wall time, so that a busy machine (a parallel build, the golden test's
parallel runs) does not make a check stop early and change what the header reports; the
checked-in models use a small fraction of every budget. A loop asks `spent()` between
samples; one long SymPy call (a determinant, a factorization) runs under `interrupting()`,
which raises BudgetSpent inside it when the budget runs out.
"""

from __future__ import annotations

import signal
import threading
import time
from contextlib import contextmanager


class BudgetSpent(Exception):
    """Raised inside a computation running under Budget.interrupting() at the deadline."""


class Budget:
    def __init__(self, seconds: float):
        self.seconds = seconds
        self._deadline = time.process_time() + seconds
        self._expired = False  # the timer fired (its clock may run a little ahead)

    def spent(self) -> bool:
        return self._expired or time.process_time() >= self._deadline

    def remaining(self) -> float:
        return max(0.0, self._deadline - time.process_time())

    @contextmanager
    def interrupting(self):
        """Runs the body until the budget is spent, then raises BudgetSpent inside it.

        Uses the profiling timer (CPU time, SIGPROF); where signals cannot be used (not the
        main thread, no setitimer) the body runs to its end and only spent() applies.
        """
        if self.spent():
            raise BudgetSpent()
        usable = (hasattr(signal, "setitimer")
                  and threading.current_thread() is threading.main_thread())
        if not usable:
            yield
            return

        def expire(signum, frame):
            self._expired = True
            raise BudgetSpent()

        previous = signal.signal(signal.SIGPROF, expire)
        signal.setitimer(signal.ITIMER_PROF, self.remaining())
        try:
            yield
        finally:
            signal.setitimer(signal.ITIMER_PROF, 0)
            signal.signal(signal.SIGPROF, previous)
