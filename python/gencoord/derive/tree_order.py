# SPDX-License-Identifier: BSD-3-Clause
"""A kinematic tree's nodes, parents before children, as the recursions walk them."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass
class Tree:
    nodes: list                  # each with `parent`: an index into nodes, or None (the root)

    def children(self) -> list[list[int]]:
        kids: list[list[int]] = [[] for _ in self.nodes]
        for index, node in enumerate(self.nodes):
            if node.parent is not None:
                kids[node.parent].append(index)
        return kids
