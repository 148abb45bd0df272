# SPDX-License-Identifier: BSD-3-Clause
"""Picks, per model, the dense or the recursive forward and inverse dynamics.

A tree model gets both (derive/kernel_set.py): `qddot` as `dynamics` (Mt and Ft + Fi)
followed by the template's LDL^T solve, or by the articulated-body recursion; `inverse_dynamics` as
Mt qdd - Ft - Fi, or by Newton-Euler. Small models favour the dense form (a pendulum's Mt
is one product), long chains the recursion (n^3 / 6 against n). After the CSE both are
counted in operations and the recursion is kept when it takes fewer than RECURSION_ADVANTAGE
times the dense form's: its steps form one long dependency chain, where the dense kernels'
independent entries keep the processor's units busy, so an operation of it costs more. A
tree of more than three coordinates takes its Mt from composite bodies, a recursion as well,
and there the form with fewer operations is kept (TREE_DERIVED_ADVANTAGE).
"""

from __future__ import annotations

from dataclasses import dataclass

from gencoord.cxx.kernel_code import KernelCode


# Measured on the planar chain at -O2, pinned to one core (scripts/bench_recursion.sh): the
# recursion's qddot equals the dense one's time at about 0.8 of its operations (n = 6, 7),
# where Mt's entries are independent sums (structured.py).
RECURSION_ADVANTAGE = 0.75
# A tree derived by its recursions computes Mt by composite bodies, itself one dependency
# chain: the form with fewer operations wins (bench_robots: the arm's articulated-body qddot
# of 1939 operations beats composite bodies and LDL^T at 2041).
TREE_DERIVED_ADVANTAGE = 1.0


def ldlt_solve_ops(n: int) -> int:
    """Operations of the template's unrolled LDL^T solve of an n x n system (solve.j2)."""
    factor = sum(3 * j + 1 + (n - 1 - j) * (2 * j + 1) for j in range(n))
    substitute = 2 * n * n - n
    return factor + substitute


@dataclass
class PathChoice:
    recursive_qddot: bool
    recursive_inverse_dynamics: bool
    report: list[str]              # one line per choice, for the generation report


def choose_paths(codes: list[KernelCode], nq: int, dynamics: str = "auto",
                 tree_derived: bool = False) -> tuple[list[KernelCode], PathChoice]:
    """The kernels with each loser of a dense/recursive pair removed, and what was chosen;
    `dynamics` "dense" or "recursive" overrides the choice. `tree_derived`: the dense
    kernels came from the recursions too (composite bodies)."""
    advantage = TREE_DERIVED_ADVANTAGE if tree_derived else RECURSION_ADVANTAGE
    recursive = {c.kernel.name: c for c in codes if c.kernel.variant == "recursive"}
    if not recursive:
        return codes, PathChoice(False, False, [])
    dense = {c.kernel.name: c for c in codes if not c.kernel.variant}
    dense_qddot = dense["dynamics"].ops + ldlt_solve_ops(nq)
    use_qddot = recursive["qddot"].ops < advantage * dense_qddot
    # a tree derived by its recursions has no dense inverse dynamics (derive/kernel_set.py)
    dense_inverse = dense.get("inverse_dynamics")
    use_inverse = (dense_inverse is None or recursive["inverse_dynamics"].ops
                   < advantage * dense_inverse.ops)
    if dynamics != "auto":
        use_qddot = use_inverse = dynamics == "recursive"
    # the dense qddot is the template's, so only a losing recursion has a kernel to drop
    losing_inverse = dense_inverse if use_inverse else recursive["inverse_dynamics"]
    dropped = {id(losing_inverse)} if losing_inverse is not None else set()
    if not use_qddot:
        dropped.add(id(recursive["qddot"]))
    report = [
        _line("qddot", use_qddot, ("articulated-body recursion", recursive["qddot"].ops),
              ("Mt, Ft + Fi and an LDL^T solve", dense_qddot)),
        _line("inverse_dynamics", use_inverse,
              ("recursive Newton-Euler", recursive["inverse_dynamics"].ops),
              ("Mt qdd - Ft - Fi", dense_inverse.ops if dense_inverse else None))]
    return ([c for c in codes if id(c) not in dropped],
            PathChoice(use_qddot, use_inverse, report))


def _line(kernel: str, use_recursive: bool, recursive: tuple[str, int],
          dense: tuple[str, int | None]) -> str:
    """`kernel: <chosen form>, <ops> operations (<other form>: <ops>)`; the other form's
    ops None: it was not generated."""
    (chosen, chosen_ops), (other, other_ops) = ((recursive, dense) if use_recursive
                                                else (dense, recursive))
    other_text = f"{other_ops}" if other_ops is not None else "n^2 operations, not generated"
    return f"{kernel}: {chosen}, {chosen_ops} operations ({other}: {other_text})"
