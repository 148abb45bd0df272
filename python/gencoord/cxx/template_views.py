# SPDX-License-Identifier: BSD-3-Clause
"""What the kernel template prints of one kernel: its code and its computed signatures."""

from __future__ import annotations

from dataclasses import dataclass

from gencoord.cxx.kernel_code import KernelCode, KernelPart
from gencoord.cxx.lvalues import cxx_type
from gencoord.cxx.signatures import kernel_arguments, part_arguments, signature


@dataclass
class PartView:
    code: KernelPart
    index: int
    member: str              # its declaration as a static member: `GENCOORD_NOINLINE ...`
    definition: str | None   # its definition outside Parts<group> (a part with a group)
    call: str                # the kernel's call of it, without the semicolon


@dataclass
class KernelView:
    code: KernelCode
    signature: str                 # `static <type> name(...)`, without the body
    result_type: str | None        # the returned block's type; None: out-parameters
    parts: list[PartView]


def _part_view(k: KernelCode, part: KernelPart, index: int, owner: str) -> PartView:
    name = f"{k.kernel.name}_part{index}"
    arguments = part_arguments(k, part)
    calls = [a.name for a in arguments[:-1]] + ["carried.data()" if k.carried_slots else "nullptr"]
    if part.group is None:
        definition, callee = None, f"{name}<Scalar>"
    else:
        definition = signature(f"  void {owner}::Parts{part.group}<Scalar>::{name}(", arguments)
        callee = f"Parts{part.group}<Scalar>::{name}"
    return PartView(part, index, signature(f"  GENCOORD_NOINLINE static void {name}(", arguments),
                    definition, f"{callee}({', '.join(calls)})")


def kernel_view(k: KernelCode, owner: str) -> KernelView:
    """The view of a kernel of struct `owner` ("Chain", "Chain::Maximal")."""
    result_type = cxx_type(k.kernel.blocks[0]) if k.kernel.returns else None
    head = f"  static {result_type or 'void'} {k.kernel.name}("
    return KernelView(k, signature(head, kernel_arguments(k)), result_type,
                      [_part_view(k, part, index, owner) for index, part in enumerate(k.parts)])
