# SPDX-License-Identifier: BSD-3-Clause
"""Every failure as one line, `file:line: error: ...`, never a traceback (but with --verbose).

The commands catch everything their work raises and pass it here: a ModelError already says
where and what; any other exception is located at the deepest model-file line of its
traceback (else just the file) and called an internal error; an interrupt is one line.
"""

from __future__ import annotations

import sys
import traceback

from gencoord.cxx.printer import UnsupportedExpression
from gencoord.errors import ModelError, model_file_line

INTERRUPTED = 130  # the shell's status for a command ended by SIGINT


def describe_failure(error: BaseException, model_path: str | None, prog: str) -> str:
    """The one line that reports `error`, whatever its message holds."""
    return " ".join(_description(error, model_path, prog).split())


def _description(error: BaseException, model_path: str | None, prog: str) -> str:
    if isinstance(error, ModelError):
        return str(error.located(model_path, None))
    if isinstance(error, KeyboardInterrupt):
        return f"{prog}: interrupted"
    if isinstance(error, UnsupportedExpression):
        return (f"{model_path}: error: {error}; use only arithmetic and elementary functions "
                "of q, t and the parameters")
    if isinstance(error, OSError) and error.filename:
        return f"{error.filename}: error: {error.strerror or error}"
    where = prog
    if model_path:
        line = model_file_line(model_path, error)
        where = model_path + (f":{line}" if line is not None else "")
    message = " ".join(str(error).split()) or "no message"  # one line, however it was raised
    if len(message) > 300:
        message = message[:300] + " ..."
    return (f"{where}: error: internal error ({type(error).__name__}: {message}); please "
            "report it with the model file (--verbose prints the traceback)")


def report_failure(error: BaseException, model_path: str | None, prog: str,
                   verbose: bool = False) -> int:
    """Prints the failure (its traceback first when `verbose`) and returns the exit status."""
    if verbose and not isinstance(error, KeyboardInterrupt):
        traceback.print_exception(type(error), error, error.__traceback__, file=sys.stderr)
    print(describe_failure(error, model_path, prog), file=sys.stderr, flush=True)
    return INTERRUPTED if isinstance(error, KeyboardInterrupt) else 1
