# SPDX-License-Identifier: BSD-3-Clause
"""Command-line words for the generated files' banners: quoted so that the shell reads them
back as the same text, and on one line whatever they hold, so that no path or option value
can end a `//` comment early (a line break) or splice the next line into it (a trailing
backslash)."""

from __future__ import annotations

import shlex


def shell_word(text: str) -> str:
    """`text` as one shell word: shlex's quoting, or bash's $'...' with escapes when it holds
    a control character (a line break, a tab)."""
    if not any(ord(char) < 32 or ord(char) == 127 for char in text):
        return shlex.quote(text)
    escaped = []
    for char in text:
        if char in "\\'":
            escaped.append("\\" + char)
        elif ord(char) < 32 or ord(char) == 127:
            escaped.append(f"\\x{ord(char):02x}")
        else:
            escaped.append(char)
    return "$'" + "".join(escaped) + "'"
