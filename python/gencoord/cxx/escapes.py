# SPDX-License-Identifier: BSD-3-Clause
"""Text written into generated files on one line, whatever it holds: C++ string literals'
contents, and the command-line words of the banners, quoted so that the shell reads them back
as the same text and so that no path or option value can end a `//` comment early (a line
break) or splice the next line into it (a trailing backslash)."""

from __future__ import annotations

import shlex


def backslash_escaped(text: str, specials: str) -> str:
    """`text` with a backslash before each of `specials` and each control character as an
    octal escape `\\NNN`, which C++ literals and bash's $'...' both read."""
    escaped = []
    for char in text:
        if char in specials:
            escaped.append("\\" + char)
        elif ord(char) < 0x20 or ord(char) == 0x7F:
            escaped.append(f"\\{ord(char):03o}")
        else:
            escaped.append(char)
    return "".join(escaped)


def shell_word(text: str) -> str:
    """`text` as one shell word: shlex's quoting, or bash's $'...' with escapes when it holds
    a control character (a line break, a tab)."""
    if not any(ord(char) < 0x20 or ord(char) == 0x7F for char in text):
        return shlex.quote(text)
    return "$'" + backslash_escaped(text, "\\'") + "'"
