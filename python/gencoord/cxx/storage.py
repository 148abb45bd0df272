# SPDX-License-Identifier: BSD-3-Clause
"""The Eigen type of a model's vectors and matrices of nq, nv and nx entries.

Fixed-size Eigen objects live on the stack, and Eigen refuses one above 128 KiB (its
EIGEN_STACK_ALLOCATION_LIMIT): a 100-link planar chain's J alone is 200 x 100 doubles,
160 KiB. A type within the limit is a fixed-size Eigen::Matrix; one beyond it is
gencoord::HeapMatrix (runtime/include/gencoord/model/heap_matrix.hpp), the same sizes on the heap,
which default-constructs at its size like a fixed-size matrix.
"""

from __future__ import annotations

# Eigen's default stack limit, in doubles (float kernels use the same types)
FIXED_SIZE_MAX_ENTRIES = 128 * 1024 // 8


def eigen_type(rows: str, columns: str, entries: int) -> str:
    """The C++ type of a matrix of `entries` entries whose sizes are spelled rows, columns."""
    template = "Eigen::Matrix" if entries <= FIXED_SIZE_MAX_ENTRIES else "gencoord::HeapMatrix"
    return f"{template}<Scalar, {rows}, {columns}>"


def model_types(nq: int, nv: int, nx: int) -> dict[str, str]:
    """QVector, QMatrix, VVector, VMatrix, VQMatrix, XVector and XJacobian of a model struct
    (templates/model_struct.j2): q has nq entries, v nv, x nx."""
    return {"QVector": eigen_type("nq", "1", nq), "QMatrix": eigen_type("nq", "nq", nq * nq),
            "VVector": eigen_type("nv", "1", nv), "VMatrix": eigen_type("nv", "nv", nv * nv),
            "VQMatrix": eigen_type("nv", "nq", nv * nq),
            "XVector": eigen_type("nx", "1", nx), "XJacobian": eigen_type("nx", "nv", nx * nv)}


def needs_heap_matrix(types: dict[str, str]) -> bool:
    return any(cxx.startswith("gencoord::HeapMatrix") for cxx in types.values())
