# SPDX-License-Identifier: BSD-3-Clause
"""Property tests (Hypothesis) of the readers of outside input. Run from the repository root
with an interpreter that has Hypothesis:
    PYTHONHASHSEED=0 /usr/bin/python3 -m unittest discover -s tests/properties -t . -v

They take about a minute (90 s with both cores busy). A run still going after 14 minutes has
hung: every thread's stack is then printed and the process exits, before CTest's 15-minute
timeout kills it with nothing printed, so that the log shows where it stopped.
"""

import faulthandler

faulthandler.dump_traceback_later(14 * 60, exit=True)
