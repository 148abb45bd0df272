# SPDX-License-Identifier: BSD-3-Clause
"""The optimizer's product: each kernel's code as C++ strings, ready for the templates."""

from __future__ import annotations

from dataclasses import dataclass, field

from gencoord.derive.kernel_set import Kernel


@dataclass
class InputsRead:
    """What straight-line code reads: a whole kernel's, or one part's of a long one."""
    coordinates: list[tuple[str, int]]     # (local name, index into q)
    rates: list[tuple[str, int]]           # (local name, index into v)
    accelerations: list[tuple[str, int]]   # (local name, index into qdd)
    parameters: list[str]                  # parameters read from params
    used_inputs: set[str]                  # the kernel inputs its expressions read
    using: list[str]                       # math functions to bring in with using std::
    sin_cos: list[str]                     # coordinates whose sin and cos one call gives


@dataclass
class KernelPart(InputsRead):
    """Statements of a long kernel emitted as a function of their own (split.py).

    `lines` is its code in order: (True, name, C++) defines a local `const Scalar name`,
    (False, lvalue, C++) assigns; the `carried` array's loads and stores are among them.
    """
    lines: list[tuple[bool, str, str]]
    uses_carried: bool
    outputs: set[str]                      # the output blocks it assigns
    # (local, source) of each Eigen output it writes through a raw pointer: lines assign
    # `local[i + rows * j]` (lvalues.element)
    data_pointers: list[tuple[str, str]] = field(default_factory=list)
    group: int | None = None               # its translation unit's part group, if any


@dataclass
class KernelCode(InputsRead):
    """A kernel ready for the template: C++ expressions as strings."""
    kernel: Kernel
    intermediates: list[tuple[str, str]]   # (tmp name, C++ expression)
    assignments: list[tuple[str, str]]     # (C++ lvalue, C++ expression)
    mirrors: list[tuple[str, str]]         # (upper lvalue, lower lvalue) of symmetric blocks
    ops: int
    parts: list[KernelPart]                # empty unless the kernel is split (split.py)
    carried_slots: int                     # size of the array the parts exchange values in
    # the blocks (their C++ targets) set to zero before the assignments, which skip their zeros
    zero_filled: list[str] = field(default_factory=list)
    body: list[str] = field(default_factory=list)  # a composed kernel's code (composed.py)
