# SPDX-License-Identifier: BSD-3-Clause
"""The C++ signatures and calls of the kernels and their parts, for the templates to print.

An argument a function does not read keeps its place in the signature with its name in a
comment (`/*params*/`), so every kernel of a model has the same parameter list shape and
compilers do not warn about unused parameters.
"""

from __future__ import annotations

from dataclasses import dataclass

from gencoord.cxx.kernel_code import KernelCode, KernelPart
from gencoord.cxx.line_wrap import LINE_WIDTH
from gencoord.cxx.lvalues import cxx_type

NESTED_INDENT = 2  # what struct Maximal adds to its kernels' lines

INPUT_TYPES = {"q": "const QVector<Scalar>& ", "v": "const VVector<Scalar>& ",
               "qdd": "const VVector<Scalar>& ", "dq": "const QVector<Scalar>& ",
               "dv": "const VVector<Scalar>& ",
               "t": "const Scalar& ", "pos": "const XVector<Scalar>& ",
               "vel": "const XVector<Scalar>& ", "kappa": "const Scalar& ",
               "penalty_damping": "const Scalar& "}


@dataclass(frozen=True)
class Argument:
    """One parameter of a C++ function: its type (with & or * and a space) and name."""
    cxx_type: str
    name: str
    used: bool = True

    def __str__(self) -> str:
        return self.cxx_type + (self.name if self.used else f"/*{self.name}*/")


def signature(head: str, arguments: list[Argument]) -> str:
    """`head` (which ends with the opening parenthesis) and the arguments, one per line,
    aligned under the first; ends with the closing parenthesis. Where that is too wide
    (with room for a nested struct's indentation), the arguments start on the next line,
    indented once more than the head."""
    texts = [str(a) for a in arguments]
    if len(head) + max(map(len, texts), default=0) + 1 <= LINE_WIDTH - NESTED_INDENT:
        return head + (",\n" + " " * len(head)).join(texts) + ")"
    indent = " " * (len(head) - len(head.lstrip(" ")) + 4)
    return head + "\n" + indent + (",\n" + indent).join(texts) + ")"


def kernel_arguments(k: KernelCode) -> list[Argument]:
    """A kernel's: its inputs, the parameters, then its out-parameters if it has any."""
    arguments = [Argument(INPUT_TYPES[name], name, name in k.used_inputs)
                 for name in k.kernel.inputs]
    # a looped kernel passes params on to the products it calls (looped.py)
    arguments.append(Argument("const Params& ", "params", bool(k.parameters or k.kernel.composed)))
    if not k.kernel.returns:
        arguments += [Argument(cxx_type(block) + "* ", block.name) for block in k.kernel.blocks]
    return arguments


def part_arguments(k: KernelCode, part: KernelPart) -> list[Argument]:
    """A part's: the inputs and parameters its kernel reads, the kernel's outputs (the
    returned one by reference), and the `carried` array; each used if the part reads it."""
    arguments = [Argument(INPUT_TYPES[name], name, name in part.used_inputs)
                 for name in k.kernel.inputs if name in k.used_inputs]
    if k.parameters:
        arguments.append(Argument("const Params& ", "params", bool(part.parameters)))
    if k.kernel.returns:
        result = k.kernel.blocks[0]
        arguments.append(Argument(cxx_type(result) + "& ", result.name, bool(part.outputs)))
    else:
        arguments += [Argument(cxx_type(block) + "* ", block.name, block.name in part.outputs)
                      for block in k.kernel.blocks]
    arguments.append(Argument("Scalar* ", "carried", part.uses_carried))
    return arguments
