# SPDX-License-Identifier: BSD-3-Clause
"""The n^2 outputs of a large tree as loops over O(n) products, so that their code grows like n.

A tree's Mt, J and residual Jacobians have n^2 entries each. Written out one statement per
entry, their code, the CSE over it and the compiler's time grow like n^2 or faster (unrolled,
the 100-link chain's header is 7.5 MB, three quarters of it these). From
GenerateOptions.loop_min_nq coordinates on, each is instead a loop over its columns, column j
the product with the unit vector e_j, and each product one forward-mode pass
(differentiate.directional_derivatives) of O(n) operations:

    Mt a        mass_matrix_product(q, qdd = a, t)        Newton-Euler's r along qdd
    J dq        jacobian_product(q, dq, t)                the positions along q
    dr/dq dq    residual_derivative_q(q, v, qdd, dq, t)   Newton-Euler's r along q
    dr/dv dv    residual_derivative_v(q, v, qdd, dv, t)   Newton-Euler's r along v

The products are kernels of their own (matrix-free solvers want Mt a without Mt). Run, a loop
takes n products of O(n), the same order as the entries it fills, where composite bodies
take O(1) per entry of Mt: the looped Mt is slower by a constant factor, and a large tree's
qddot never reads it (the articulated-body recursion is chosen there).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from gencoord.derive.dense import Derivation
from gencoord.derive.kernel_set import Block, Call, Composed, Kernel


@dataclass
class LoopedOutputs:
    """The looped kernels by the name of the unrolled kernel each replaces, the products they
    call, and the direction inputs' symbols with their C++ spellings."""
    replacing: dict[str, Kernel]
    products: list[Kernel]
    names: dict[sp.Symbol, str]          # a direction's entries: dq(0), dq(1), ...
    input_of: dict[sp.Symbol, str]       # each to its kernel argument, "dq" or "dv"


def _direction(argument: str, n: int) -> list[sp.Symbol]:
    # '__' cannot start a model's names (validate.py)
    return [sp.Symbol(f"__{argument}{j}") for j in range(n)]


def _product(name: str, summary: str, inputs: tuple[str, ...], storage: str,
             of: sp.Matrix, seeds: dict[sp.Symbol, sp.Expr]) -> Kernel:
    return Kernel(name, summary, inputs,
                  [Block("result", storage, (len(of), 1), [], tangent_of=(list(of), seeds))])


def looped_outputs(d: Derivation, residual: sp.Matrix) -> LoopedOutputs:
    """The looped kernels of a tree whose derivation has no Mt or J, with `residual` its
    Newton-Euler r(q, v, qdd, t)."""
    nq = len(d.q)
    dq, dv = _direction("dq", nq), _direction("dv", nq)
    products = [
        _product("mass_matrix_product", "Mt qdd without Mt: the derivative of Newton-Euler's "
                 "residual along qdd (O(nq)).", ("q", "qdd", "t"), "VVector",
                 residual, dict(zip(d.a, d.a))),
        _product("jacobian_product", "J dq without J: the derivative of the positions along dq "
                 "(O(nq)).", ("q", "dq", "t"), "XVector", d.positions,
                 dict(zip(d.q, dq))),
        _product("residual_derivative_q", "dr/dq dq: the derivative of Newton-Euler's residual "
                 "along dq (O(nq)).", ("q", "v", "qdd", "dq", "t"), "VVector",
                 residual, dict(zip(d.q, dq))),
        _product("residual_derivative_v", "dr/dv dv: the derivative of Newton-Euler's residual "
                 "along dv (O(nq)).", ("q", "v", "qdd", "dv", "t"), "VVector",
                 residual, dict(zip(d.v, dv))),
    ]
    looped = "a loop over its nq columns, each a product (O(nq^2) in all)"
    replacing = {
        "mass_matrix": Kernel(
            "mass_matrix", f"Reduced mass matrix Mt = J^T M J (symmetric), by {looped}.",
            ("q", "t"), [Block("result", "VMatrix", (nq, nq), [])],
            composed=Composed((Call("result", "mass_matrix_product", ("q", "unit", "t")),),
                              columns=nq)),
        "dynamics": Kernel(
            "dynamics", "Mt and Ft + Fi.", ("q", "v", "t"),
            [Block("Mt", "VMatrix", (nq, nq), [], out_param=True),
             Block("f", "VVector", (nq, 1), [], out_param=True)],
            notes=["Mt and f must not be null."],
            composed=Composed((Call("Mt", "mass_matrix", ("q", "t")),
                               Call("f", "forces", ("q", "v", "t"))))),
        "residual_jacobians": Kernel(
            "residual_jacobians", "Jacobians dr/dq and dr/dv of the residual (dr/dqdd = Mt), "
            f"for Newton steps, by {looped}.", ("q", "v", "qdd", "t"),
            [Block("dr_dq", "VQMatrix", (nq, nq), [], out_param=True),
             Block("dr_dv", "VMatrix", (nq, nq), [], out_param=True)],
            notes=["dr_dq and dr_dv must not be null."],
            composed=Composed(
                (Call("dr_dq", "residual_derivative_q", ("q", "v", "qdd", "unit", "t")),
                 Call("dr_dv", "residual_derivative_v", ("q", "v", "qdd", "unit", "t"))),
                columns=nq)),
        "jacobian": Kernel(
            "jacobian", f"Jacobian J = dX/dq, by {looped}.", ("q", "t"),
            [Block("result", "XJacobian", (len(d.positions), nq), [])],
            composed=Composed((Call("result", "jacobian_product", ("q", "unit", "t")),),
                              columns=nq)),
    }
    names = {**{s: f"dq({j})" for j, s in enumerate(dq)},
             **{s: f"dv({j})" for j, s in enumerate(dv)}}
    input_of = {**{s: "dq" for s in dq}, **{s: "dv" for s in dv}}
    return LoopedOutputs(replacing, products, names, input_of)
