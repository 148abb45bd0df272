# SPDX-License-Identifier: BSD-3-Clause
"""The C++ body of a composed kernel (derive/kernel_set.Composed): calls of the model's other
kernels, once each, or once per column j along the unit vector e_j in a loop."""

from __future__ import annotations

from gencoord.derive.kernel_set import Call, Kernel


def composed_body(kernel: Kernel) -> list[str]:
    composed = kernel.composed
    assert composed is not None, kernel.name
    looped = composed.columns > 0

    def target(call: Call) -> str:
        if call.output == kernel.returns:
            return "result.col(j)" if looped else "result"
        return f"{call.output}->col(j)" if looped else f"*{call.output}"

    lines = [f"{target(call)} = {call.kernel}({', '.join((*call.inputs, 'params'))});"
             for call in composed.calls]
    if not looped:
        return lines
    return ["QVector<Scalar> unit = QVector<Scalar>::Zero();",
            "for (int j = 0; j < nq; ++j) {",
            "  unit(j) = Scalar(1);",
            *[f"  {line}" for line in lines],
            "  unit(j) = Scalar(0);",
            "}"]
