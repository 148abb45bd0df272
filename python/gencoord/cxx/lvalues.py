# SPDX-License-Identifier: BSD-3-Clause
"""An output block in C++: its type, the expression of the whole block, and the lvalue of one
entry in a whole kernel or in a part."""

from __future__ import annotations

from gencoord.derive.kernel_set import Block


def cxx_type(block: Block) -> str:
    """`QMatrix<Scalar>` and the like, `Scalar`, or `std::array<Scalar, n>`."""
    if block.is_scalar:
        return "Scalar"
    if block.array:
        return f"std::array<Scalar, {block.shape[0]}>"
    return f"{block.storage}<Scalar>"


def target(block: Block) -> str:
    """The whole output inside its kernel: `result`, or `(*Mt)` through its pointer."""
    return f"(*{block.name})" if block.out_param else block.name


def lvalue(block: Block, i: int, j: int) -> str:
    """Entry (i, j) through Eigen's operator() (or the array's [], or the scalar itself)."""
    if block.is_scalar:
        return target(block)
    if block.array:
        return f"{target(block)}[{i}]"
    if block.shape[1] == 1:
        return f"{target(block)}({i})"
    return f"{target(block)}({i}, {j})"


def data_pointer(block: Block) -> tuple[str, str]:
    """(local, source) of the raw pointer a part writes an Eigen output block through."""
    source = f"{block.name}->data()" if block.out_param else f"{block.name}.data()"
    return f"{block.name}_data", source


def writes_through_pointer(block: Block) -> bool:
    return not (block.is_scalar or block.array)


def element(block: Block, i: int, j: int) -> str:
    """The lvalue of entry (i, j) of `block` in a part: the column-major element through its
    data pointer, not Eigen's operator(). GCC then has no call to resolve and inline per
    statement, which takes about a tenth off compiling a 50-link chain's parts."""
    if not writes_through_pointer(block):
        return lvalue(block, i, j)
    local = data_pointer(block)[0]
    if block.shape[1] == 1:
        return f"{local}[{i}]"
    return f"{local}[{i} + {block.shape[0]} * {j}]"
