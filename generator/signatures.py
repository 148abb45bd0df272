"""The C++ signatures and calls of the kernels and their parts, for the templates to print.

An argument a function does not read keeps its place in the signature with its name in a
comment (`/*params*/`), so every kernel of a model has the same parameter list shape and
compilers do not warn about unused parameters.
"""

from __future__ import annotations

from dataclasses import dataclass

from .kernel_code import KernelCode, KernelPart

INPUT_TYPES = {"q": "const QVector<Scalar>& ", "v": "const QVector<Scalar>& ",
               "qdd": "const QVector<Scalar>& ",
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
    aligned under the first; ends with the closing parenthesis."""
    return head + (",\n" + " " * len(head)).join(map(str, arguments)) + ")"


def kernel_arguments(k: KernelCode) -> list[Argument]:
    """A kernel's: its inputs, the parameters, then its out-parameters if it has any."""
    arguments = [Argument(INPUT_TYPES[name], name, name in k.used_inputs)
                 for name in k.kernel.inputs]
    arguments.append(Argument("const Params& ", "params", bool(k.parameters)))
    if not k.kernel.returns:
        arguments += [Argument(block.cxx_type + "* ", block.name) for block in k.kernel.blocks]
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
        arguments.append(Argument(result.cxx_type + "& ", result.name, bool(part.outputs)))
    else:
        arguments += [Argument(block.cxx_type + "* ", block.name, block.name in part.outputs)
                      for block in k.kernel.blocks]
    arguments.append(Argument("Scalar* ", "carried", part.uses_carried))
    return arguments
