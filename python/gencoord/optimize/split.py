# SPDX-License-Identifier: BSD-3-Clause
"""Cuts a long kernel into part functions, so the C++ compiler's time stays near linear.

GCC's register allocation grows much faster than linearly with the size of one function:
the 50-link chain's residual_jacobians, about 19,000 statements in one function, took 244 s
to compile at -O2, 117 s of it in LRA hard-register assignment. A kernel over
GenerateOptions.part_statements statements (options.py) is emitted as consecutive parts of
nearly equal size, each its own function that is never inlined; the kernel calls them in
order. An intermediate that one part computes and a later part reads travels through a slot
of an array the kernel owns.

Statements keep their order, except that each output assignment moves up to just after the
last intermediate it reads (a Jacobian's column is stored as soon as it is known), so fewer
values cross from part to part. A value is loaded right before its first use in a part and
stored right after it is computed, so nothing stays live across a whole part; a slot is
reused once the parts that read its value are done.
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass


@dataclass
class PartPlan:
    """One part: the kernel statements it runs, in order, and its exchanges with `carried`."""
    statements: list[int]                   # indices into the kernel's statements
    loads: dict[int, list[tuple[str, int]]]  # statement -> (name, slot) to load just before
    stores: dict[int, int]                  # statement -> slot its value is stored in


def _with_assignments_early(defines: list[str | None], reads: list[set[str]]) -> list[int]:
    """Statement order with each assignment (defines None) right after what it reads."""
    position = {name: k for k, name in enumerate(defines) if name}
    after: dict[int, list[int]] = {}
    for k, name in enumerate(defines):
        if name is None:
            after.setdefault(max((position[r] for r in reads[k] if r in position),
                                 default=-1), []).append(k)
    order = list(after.get(-1, []))
    for k, name in enumerate(defines):
        if name is not None:
            order.append(k)
            order.extend(after.get(k, []))
    return order


def plan_parts(defines: list[str | None], reads: list[set[str]],
               max_statements: int,
               always: bool = False) -> tuple[list[PartPlan], int]:
    """The parts of a kernel whose statement k defines the intermediate `defines[k]` (None
    for an output assignment) and reads the intermediates `reads[k]`; and the number of
    slots of `carried` they need.

    Returns ([], 0) when the kernel fits in one function or `max_statements` is 0, unless
    `always` (kernels compiled in translation units of their own): then a kernel with any
    statement is at least one part. Deterministic: slots are taken lowest first.
    """
    count = len(defines)
    fits = max_statements <= 0 or count <= max_statements
    if count == 0 or (fits and not always):
        return [], 0
    order = _with_assignments_early(defines, reads)
    parts = 1 if fits else -(-count // max_statements)
    bounds = [count * p // parts for p in range(parts + 1)]
    chunks = [order[bounds[p]:bounds[p + 1]] for p in range(parts)]
    part_of = {k: p for p, chunk in enumerate(chunks) for k in chunk}
    defined_at = {name: k for k, name in enumerate(defines) if name}

    # the first statement of each part that reads a value from an earlier part
    first_use: list[dict[str, int]] = [{} for _ in range(parts)]
    last_part: dict[str, int] = {}
    for p, chunk in enumerate(chunks):
        for k in chunk:
            for name in sorted(reads[k]):
                home = defined_at.get(name)
                if home is not None and part_of[home] < p:
                    first_use[p].setdefault(name, k)
                    last_part[name] = p

    slot_of: dict[str, int] = {}
    free: list[int] = []
    slots = 0
    plans = []
    for p, chunk in enumerate(chunks):
        stores = {}
        for k in chunk:
            defined = defines[k]
            if defined and defined in last_part:
                if free:
                    slot_of[defined] = heapq.heappop(free)
                else:
                    slot_of[defined], slots = slots, slots + 1
                stores[k] = slot_of[defined]
        loads: dict[int, list[tuple[str, int]]] = {}
        for name, k in first_use[p].items():
            loads.setdefault(k, []).append((name, slot_of[name]))
        for entries in loads.values():
            entries.sort(key=lambda entry: defined_at[entry[0]])
        plans.append(PartPlan(chunk, loads, stores))
        # this part may load a value after storing others: slots free up once it is done
        for name in first_use[p]:
            if last_part[name] == p:
                heapq.heappush(free, slot_of[name])
    return plans, slots


def assign_groups(sizes: list[int], groups: int) -> list[int]:
    """The group (translation unit) of each part, given the parts' statement counts.

    Largest part first to the group with the fewest statements so far (ties: lowest group),
    so the groups compile in about equal time; deterministic.
    """
    load = [(0, g) for g in range(groups)]
    group_of = [0] * len(sizes)
    for k in sorted(range(len(sizes)), key=lambda k: (-sizes[k], k)):
        total, g = heapq.heappop(load)
        group_of[k] = g
        heapq.heappush(load, (total + sizes[k], g))
    return group_of


def is_derivative_path(kernel_name: str) -> bool:
    """Whether a kernel is one of those that run back to back on the derivative path
    (dynamics_derivatives: `dynamics`, then `residual_jacobians`) or is another Jacobian.

    Group 0 holds the other kernels' parts once there are two groups or more, and CMake
    compiles it with GCC's register-pressure-aware scheduling before register allocation
    (gencoord_add_model), which shortens the latency-bound kernels (a 7-joint arm's
    inverse_dynamics by about a sixth) but lengthens long code (the arm's residual_jacobians
    by a seventh). The derivative path's code nearly fills a 64 KiB instruction cache on a
    7-joint arm, so it keeps the default scheduling: grown by it, it ran half as long again
    (docs/performance.md, section 9).
    """
    return kernel_name == "dynamics" or "jacobian" in kernel_name


def assign_role_groups(sizes: list[int], derivative_path: list[bool],
                       groups: int) -> list[int]:
    """The group of each part, given its statement count and whether its kernel is on the
    derivative path (is_derivative_path): with one group, all are group 0; with more, the
    others fill group 0 and the derivative path is balanced over groups 1 and up
    (assign_groups). Deterministic."""
    if groups < 2:
        return [0] * len(sizes)
    apart = [k for k, on_path in enumerate(derivative_path) if on_path]
    group_of = [0] * len(sizes)
    for k, group in zip(apart, assign_groups([sizes[k] for k in apart], groups - 1)):
        group_of[k] = group + 1
    return group_of
