# SPDX-License-Identifier: BSD-3-Clause
"""The one error type of the gencoord command: a message for the user, no traceback."""


class ToolError(Exception):
    """Printed as `gencoord: error: <message>`; `shown`: the details were already printed.
    Exit status 1."""

    prefix = "gencoord: error: "  # none for a message that starts with its own location

    def __init__(self, message: str, *, shown: bool = False):
        super().__init__(message)
        self.shown = shown
