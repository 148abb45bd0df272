# SPDX-License-Identifier: BSD-3-Clause
"""A sweep file as read: its text, its TOML, and the line of each key, so that every error
names the file, the line and the key (`flip.toml:12: error: samples.q.theta1.points: ...`)."""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass, field

from gencoord.tool.errors import ToolError

if sys.version_info >= (3, 11):
    import tomllib
else:
    tomllib = None

Key = tuple[str, ...]

_KEY_PART = r'(?:[A-Za-z0-9_-]+|"[^"]*"|\'[^\']*\')'
_DOTTED = rf"{_KEY_PART}(?:\s*\.\s*{_KEY_PART})*"
_TABLE_HEADER = re.compile(rf"^\s*\[\s*({_DOTTED})\s*\]\s*(?:#.*)?$")
_KEY_LINE = re.compile(rf"^\s*({_DOTTED})\s*=")
_TOML_POSITION = re.compile(r"\s*\(at line (\d+), column \d+\)$")


class SweepFileError(ToolError):
    """An error in a sweep file, printed as `FILE:LINE: error: KEY: what, and what to do`."""
    prefix = ""


def key_text(key: Key) -> str:
    return ".".join(key)


def _split(dotted: str) -> Key:
    return tuple(part.strip("\"'") for part in re.findall(_KEY_PART, dotted))


def key_lines(text: str) -> dict[Key, int]:
    """The line (from 1) where each table header and each key is written. Keys inside an
    inline table are found at their table's line (the caller falls back to the parent)."""
    lines: dict[Key, int] = {}
    table: Key = ()
    for number, line in enumerate(text.splitlines(), start=1):
        header = _TABLE_HEADER.match(line)
        if header:
            table = _split(header.group(1))
            lines.setdefault(table, number)
            continue
        if line.lstrip().startswith("[["):
            table = ()
            continue
        assignment = _KEY_LINE.match(line)
        if assignment:
            lines.setdefault(table + _split(assignment.group(1)), number)
    return lines


@dataclass(frozen=True)
class SweepSource:
    """The file's path (as given), text and TOML data."""
    path: str
    text: str
    data: dict
    lines: dict[Key, int] = field(default_factory=dict)

    def line_of(self, key: Key) -> int | None:
        """The line of `key`, else of its nearest enclosing key written in the file."""
        for end in range(len(key), 0, -1):
            if key[:end] in self.lines:
                return self.lines[key[:end]]
        return None

    def error(self, key: Key, message: str) -> SweepFileError:
        line = self.line_of(key)
        where = self.path + (f":{line}" if line else "")
        subject = f"{key_text(key)}: " if key else ""
        return SweepFileError(f"{where}: error: {subject}{message}")


def read_source(path: str) -> SweepSource:
    """Reads and parses a sweep file; a TOML syntax error names its line."""
    if tomllib is None:
        raise ToolError("gencoord sweep needs Python 3.11 or newer (tomllib)")
    try:
        with open(path, "rb") as handle:
            raw = handle.read()
    except OSError as error:
        raise ToolError(f"{path}: cannot read the sweep file: {error.strerror or error}") \
            from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as error:
        raise SweepFileError(f"{path}: error: not UTF-8 text (byte {error.start}); a sweep "
                             "file is TOML, which is UTF-8") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        message = str(error)
        position = _TOML_POSITION.search(message)
        where = f"{path}:{position.group(1)}" if position else path
        message = _TOML_POSITION.sub("", message)
        raise SweepFileError(f"{where}: error: {message} (not valid TOML; see "
                             "docs/sweep.md for the file's form)") from None
    return SweepSource(path=path, text=text, data=data, lines=key_lines(text))
