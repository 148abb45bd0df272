# SPDX-License-Identifier: BSD-3-Clause
"""Errors a model file can cause, each naming the file, the line and the item."""

from __future__ import annotations

import os
import traceback


class ModelError(Exception):
    """A problem in a user's model file.

    The message always says where (file and line when known), which item (a particle, a
    coordinate, a force ...) and what to do about it.
    """

    def __init__(self, message: str, *, item: str | None = None,
                 filename: str | None = None, line: int | None = None):
        self.message = message
        self.item = item
        self.filename = filename
        self.line = line
        super().__init__(self.__str__())

    def located(self, filename: str | None, line: int | None) -> "ModelError":
        """Returns a copy that carries a location, keeping one it already has."""
        return ModelError(self.message, item=self.item,
                          filename=self.filename or filename,
                          line=self.line if self.line is not None else line)

    def __str__(self) -> str:
        where = ""
        if self.filename:
            where = self.filename + (f":{self.line}" if self.line is not None else "") + ": "
        what = f"{self.item}: " if self.item else ""
        return f"{where}error: {what}{self.message}"


def model_file_line(path: str, error: BaseException) -> int | None:
    """The deepest line of the model file `path` in an exception's traceback."""
    line = None
    for frame in traceback.extract_tb(error.__traceback__):
        if os.path.abspath(frame.filename) == os.path.abspath(path):
            line = frame.lineno
    return line
