# SPDX-License-Identifier: BSD-3-Clause
"""Reads an XML file into ElementTree elements that remember their line, and reads their
attributes as numbers; every failure is a ModelError at the file and line."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from xml.parsers import expat

from gencoord.errors import ModelError


class XmlFile:
    """The parsed file: `root`, each element's line (`line(element)`) and the comments that
    come before the root element."""

    def __init__(self, path: str):
        self.path = path
        self._lines: dict[int, int] = {}
        self.leading_comments: list[str] = []
        builder = ET.TreeBuilder()
        parser = expat.ParserCreate()

        def start(tag, attributes):
            # the element stays alive in the tree, so its id() is a stable key
            self._lines[id(builder.start(tag, attributes))] = parser.CurrentLineNumber

        def comment(text):
            if not self._lines:
                self.leading_comments.append(text)

        parser.StartElementHandler = start
        parser.EndElementHandler = builder.end
        parser.CharacterDataHandler = builder.data
        parser.CommentHandler = comment
        try:
            with open(path, "rb") as handle:
                data = handle.read()
            # in one piece: fed in blocks, expat rescans a long token (a 5 MB comment) at every
            # block, which is quadratic
            parser.Parse(data, True)
        except OSError as error:
            raise ModelError(f"cannot read the file: {error.strerror}", filename=path) from None
        except expat.ExpatError as error:
            raise ModelError(f"malformed XML: {expat.ErrorString(error.code)} (column "
                             f"{error.offset + 1}); fix the XML", filename=path,
                             line=error.lineno) from None
        self.root = builder.close()

    def line(self, element: ET.Element) -> int | None:
        return self._lines.get(id(element))

    def error(self, message: str, element: ET.Element, item: str | None = None) -> ModelError:
        """A ModelError at the element's line, naming `item` (default: the element's tag)."""
        return ModelError(message, item=item or f"<{element.tag}>", filename=self.path,
                          line=self.line(element))

    def numbers(self, element: ET.Element, attribute: str, count: int, default=None,
                item: str | None = None) -> list[float]:
        """The attribute's `count` whitespace-separated finite numbers; `default` when the
        attribute is absent (None: it is required)."""
        text = element.get(attribute)
        where = f"<{element.tag} {attribute}=\"{text}\">"
        if text is None:
            if default is not None:
                return list(default)
            raise self.error(f"<{element.tag}> needs the attribute {attribute}", element, item)
        try:
            values = [float(word) for word in text.split()]
        except ValueError:
            hint = " (expand the xacro expressions first)" if "$" in text else ""
            raise self.error(f"{where} is not a list of numbers; write plain decimal numbers"
                             f"{hint}", element, item) from None
        if len(values) != count:
            raise self.error(f"{where} has {len(values)} numbers; give {count}", element, item)
        if not all(math.isfinite(v) for v in values):
            raise self.error(f"{where} is not finite; give finite numbers", element, item)
        return values

    def number(self, element: ET.Element, attribute: str, default: float | None = None,
               item: str | None = None) -> float:
        value = default if default is None else [default]
        return self.numbers(element, attribute, 1, value, item)[0]
