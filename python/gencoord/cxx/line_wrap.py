# SPDX-License-Identifier: BSD-3-Clause
"""Wraps the lines of generated C++ that are wider than LINE_WIDTH columns.

Code breaks at the outermost level that has a break: before a binary + or -, else after a
comma, else before a * or /; a piece still too long is broken inside the bracket group it
holds. Continuation lines are indented by CONTINUATION_INDENT more than the line they
continue. Comment lines break between words under the same `//` prefix. Only whitespace
changes, and the same text always wraps the same way. A line without any break (a single
token wider than the limit, or a preprocessor line) stays as it is, and so does the banner's
command line, which a reader copies whole.
"""

from __future__ import annotations

LINE_WIDTH = 100
CONTINUATION_INDENT = 4
_OPEN, _CLOSE = "([{<", ")]}>"
COMMAND_MARKER = "regenerate: "  # the banner line holding the command that regenerates a file


def _depths(text: str) -> list[int | None]:
    """The bracket depth before each character; None inside a string literal (its quotes
    have the depth) and from the first comment on. A `<` opens a template argument list
    only right after a name (`array<int`), never in `i < n`."""
    depths: list[int | None] = []
    depth, quoted = 0, False
    for k, char in enumerate(text):
        if not quoted and text[k:k + 2] in ("//", "/*"):  # a comment, never broken
            return depths + [None] * (len(text) - k)
        if char == '"' and not (quoted and text[k - 1:k] == "\\"):
            depths.append(depth)
            quoted = not quoted
            continue
        if quoted:
            depths.append(None)
            continue
        depths.append(depth)
        before = text[k - 1:k]
        if char in "([{" or (char == "<" and (before.isalnum() or before == "_")):
            depth += 1
        elif char in ")]}" or (char == ">" and before not in ("-", " ") and depth > 0):
            depth -= 1
    return depths


def _breaks(text: str, depths: list[int | None], kind: str) -> list[int]:
    """Where top-level pieces of `kind` start: the operator's or the next item's index."""
    found = []
    for k in range(1, len(text) - 1):
        if depths[k] != 0:
            continue
        char, before, after = text[k], text[k - 1], text[k + 1]
        if kind == "sum" and char in "+-" and before == " " and after == " ":
            found.append(k)
        elif kind == "comma" and char == "," and after == " ":
            found.append(k + 2)
        elif kind == "product" and char in "*/" and before != " " and after != " ":
            found.append(k)
    return found


def _pieces(text: str, depths: list[int | None], kinds: tuple[str, ...]) -> list[str]:
    """The top-level pieces of `text` at the first of `kinds` it has, stripped."""
    for kind in kinds:
        starts = _breaks(text, depths, kind)
        if starts:
            bounds = [0, *starts, len(text)]
            return [text[a:b].strip() for a, b in zip(bounds, bounds[1:])]
    return [text]


def _joiner(piece: str) -> str:
    """What stands before `piece` when it joins the one before on a line."""
    return "" if piece[:1] in "*/" else " "


def _widest_group(text: str, depths: list[int | None]) -> tuple[int, int] | None:
    """(start, end) of the contents of the widest top-level bracket group, if any."""
    best, start = None, None
    for k, char in enumerate(text):
        if depths[k] == 0 and char in _OPEN and k + 1 < len(text) and depths[k + 1] == 1:
            start = k + 1
        elif (start is not None and depths[k] == 1 and char in _CLOSE
              and (k + 1 == len(text) or depths[k + 1] == 0)):
            if best is None or k - start > best[1] - best[0]:
                best = (start, k)
            start = None
    return best


def wrap_code(text: str, column: int, continuation: int) -> list[str]:
    """`text` placed at `column` as lines within LINE_WIDTH: the first line as it starts
    there, the others with their indentation (`continuation` spaces, more for nesting)."""
    if column + len(text) <= LINE_WIDTH:
        return [text]
    depths = _depths(text)
    pieces = _pieces(text, depths, ("sum", "comma"))
    if len(pieces) == 1:
        lines = _wrap_group(text, depths, column, continuation)
        if len(lines) > 1:
            return lines
        pieces = _pieces(text, depths, ("product",))
        if len(pieces) == 1:
            return [text]
    return _pack(pieces, column, continuation)


def _wrap_group(text: str, depths: list[int | None], column: int,
                continuation: int) -> list[str]:
    """`text` (bracket depths `depths`) broken inside its widest top-level bracket group."""
    group = _widest_group(text, depths)
    if group is None:
        return [text]
    # the group's contents with what follows its closing bracket (`}};`), so that the last
    # line has room for it
    start = group[0]
    inner = wrap_code(text[start:], column + start, continuation)
    if len(inner) == 1:
        return [text]
    if column + start + len(inner[0]) <= LINE_WIDTH:
        return [text[:start] + inner[0], *inner[1:]]
    # no room for the first item after the bracket: the contents start on a new line
    inner = wrap_code(text[start:], continuation, continuation)
    return [text[:start], " " * continuation + inner[0], *inner[1:]]


def _pack(pieces: list[str], column: int, continuation: int) -> list[str]:
    """As many pieces on each line as fit; a piece too long alone is wrapped in turn."""
    lines: list[str] = []
    current, at = pieces[0], column
    for piece in pieces[1:]:
        joined = current + _joiner(piece) + piece
        if at + len(joined) <= LINE_WIDTH:
            current = joined
            continue
        wrapped = wrap_code(current, at, continuation + CONTINUATION_INDENT)
        lines += [wrapped[0] if not lines else " " * continuation + wrapped[0], *wrapped[1:]]
        current, at = piece, continuation
    wrapped = wrap_code(current, at, continuation + CONTINUATION_INDENT)
    lines += [wrapped[0] if not lines else " " * continuation + wrapped[0], *wrapped[1:]]
    return lines


def _wrap_comment(line: str, indent: int) -> list[str]:
    """A `//` comment line broken between words, each line under the same prefix."""
    body = line[indent:]
    marker = len(body) - len(body.lstrip("/"))
    text = body[marker:]
    prefix = line[:indent + marker] + text[:len(text) - len(text.lstrip(" "))]
    words = text.strip().split(" ")
    lines, current = [], prefix + words[0]
    for word in words[1:]:
        if len(current) + 1 + len(word) > LINE_WIDTH and current.strip() != prefix.strip():
            lines.append(current)
            current = prefix + word
        else:
            current += " " + word
    return lines + [current]


def wrap_prose(line: str, width: int) -> list[str]:
    """A line of text (a model file's docstring) broken between words within `width` columns,
    each piece with the line's own indentation; a word wider than that stays whole. A line
    that fits stays as it is (drawings keep their spacing)."""
    if len(line) <= width:
        return [line]
    indent = line[:len(line) - len(line.lstrip(" "))]
    words = line.split()
    if not words:
        return [""]
    lines, current = [], indent + words[0]
    for word in words[1:]:
        if len(current) + 1 + len(word) > width:
            lines.append(current)
            current = indent + word
        else:
            current += " " + word
    return lines + [current]


def wrap_line(line: str) -> list[str]:
    if len(line) <= LINE_WIDTH:
        return [line]
    indent = len(line) - len(line.lstrip(" "))
    text = line[indent:]
    if text.startswith("//"):
        return [line] if COMMAND_MARKER in text else _wrap_comment(line, indent)
    if text.startswith("#"):
        return [line]
    lines = wrap_code(text, indent, indent + CONTINUATION_INDENT)
    return [" " * indent + lines[0], *lines[1:]]


def wrap_long_lines(text: str) -> str:
    """Every line of `text` within LINE_WIDTH columns where it has a place to break."""
    return "\n".join(wrapped for line in text.split("\n") for wrapped in wrap_line(line))
