# SPDX-License-Identifier: BSD-3-Clause
"""A model file's build options (`generate --set n=5`): where the requested values come from,
and how one is read and checked against its declaration (`Model.option`)."""

from __future__ import annotations

import contextlib
import math
from contextvars import ContextVar
from types import MappingProxyType
from typing import Iterator, Mapping

from gencoord.errors import ModelError
from gencoord.dsl.items import caller_line

# The model options requested of the model file being run: a Model built while the loader
# runs the file takes them, since the file itself only says `Model(dim=2)`.
REQUESTED_OPTIONS: ContextVar[Mapping[str, str]] = ContextVar(
    "gencoord_requested_options", default=MappingProxyType({}))


@contextlib.contextmanager
def requesting_options(options: Mapping[str, str]) -> Iterator[None]:
    """Every Model built inside the block takes these requested options (a read-only view;
    each Model copies them)."""
    token = REQUESTED_OPTIONS.set(MappingProxyType(options))
    try:
        yield
    finally:
        REQUESTED_OPTIONS.reset(token)


def option_value(name: str, raw: str, default, description: str, minimum, maximum):
    """The requested text `raw` of option `name` as the default's type, finite and inside
    [minimum, maximum] (a bound of None is open); anything else is a located ModelError."""
    item, line = f"option '{name}'", caller_line()
    try:
        value = type(default)(raw)
    except ValueError:
        raise ModelError(f"--set {name}={raw} is not a {type(default).__name__}",
                         item=item, line=line)
    if isinstance(value, float) and not math.isfinite(value):
        raise ModelError(f"--set {name}={raw} is not finite", item=item, line=line)
    if (minimum is not None and value < minimum) or (maximum is not None and value > maximum):
        raise ModelError(f"--set {name}={raw} is outside the option's range "
                         f"{_range_text(minimum, maximum)} ({description})", item=item, line=line)
    return value


def _range_text(minimum, maximum) -> str:
    """An option's range as the refusal states it: `[1, 100]`, `>= 1` or `<= 100`."""
    if minimum is not None and maximum is not None:
        return f"[{minimum}, {maximum}]"
    return f">= {minimum}" if minimum is not None else f"<= {maximum}"
