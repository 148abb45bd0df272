# SPDX-License-Identifier: BSD-3-Clause
"""Cutting long kernels into parts (gencoord/optimize/split.py): the plan runs like the whole
kernel.

Each plan is executed on a model of the emitted code: statements in the planned order, every
intermediate a local of its part, `carried` an array of slots. A load must find in its slot
the very value a store put there (so no slot is reused too early), every read must see a
value defined before it in the same part or loaded into it, and every statement must run
exactly once. The C++ side (tests/models/split_kernels_test.cc) checks the emitted parts
compute what the whole kernels compute.
"""

from __future__ import annotations

import random
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

from gencoord.generate.stages import generate
from gencoord.options import GenerateOptions
from gencoord.optimize.split import plan_parts

from .support import REPO


def _random_kernel(rng: random.Random, intermediates: int, outputs: int):
    """A random straight-line program: each intermediate reads up to 4 earlier ones."""
    defines, reads = [], []
    for k in range(intermediates):
        defines.append(f"t{k}")
        reads.append({f"t{rng.randrange(k)}" for _ in range(rng.randint(0, 4))} if k else set())
    for _ in range(outputs):
        defines.append(None)
        reads.append({f"t{rng.randrange(intermediates)}" for _ in range(rng.randint(1, 3))})
    return defines, reads


def _execute(test: unittest.TestCase, defines, reads, plans, slots):
    """Runs the plan on the model described in the module docstring."""
    carried: list[str | None] = [None] * slots
    executed = []
    for plan in plans:
        local: set[str] = set()
        for k in plan.statements:
            for name, slot in plan.loads.get(k, []):
                test.assertEqual(carried[slot], name, f"slot {slot} lost {name}")
                local.add(name)
            for name in reads[k]:
                test.assertIn(name, local, f"statement {k} reads {name} before it is known")
            if defines[k]:
                local.add(defines[k])
            if k in plan.stores:
                test.assertIsNotNone(defines[k])
                carried[plan.stores[k]] = defines[k]
            executed.append(k)
    test.assertEqual(sorted(executed), list(range(len(defines))))


class PlanPartsTest(unittest.TestCase):

    def test_short_kernels_stay_whole(self):
        defines, reads = _random_kernel(random.Random(1), 30, 10)
        self.assertEqual(plan_parts(defines, reads, 40), ([], 0))
        self.assertEqual(plan_parts(defines, reads, 0), ([], 0))

    def test_random_programs_run_as_planned(self):
        rng = random.Random(7)
        for _ in range(200):
            defines, reads = _random_kernel(rng, rng.randint(2, 120), rng.randint(1, 40))
            size = rng.randint(1, 30)
            plans, slots = plan_parts(defines, reads, size)
            if len(defines) <= size:
                self.assertEqual(plans, [])
                continue
            self.assertEqual(len(plans), -(-len(defines) // size))
            self.assertTrue(all(len(plan.statements) <= size for plan in plans))
            _execute(self, defines, reads, plans, slots)

    def test_assignments_follow_what_they_read(self):
        # a Jacobian's columns: each output reads one chain of intermediates, so moving
        # outputs up means later parts need no values from earlier parts
        defines, reads = [], []
        for column in range(6):
            for k in range(10):
                defines.append(f"c{column}_{k}")
                reads.append({f"c{column}_{k - 1}"} if k else set())
        for column in range(6):
            defines.append(None)
            reads.append({f"c{column}_9"})
        plans, slots = plan_parts(defines, reads, 11)
        _execute(self, defines, reads, plans, slots)
        self.assertEqual(slots, 0)

    def test_slots_are_reused(self):
        # a long chain: each part hands one value on, so one slot does
        defines = [f"t{k}" for k in range(100)]
        reads = [set()] + [{f"t{k - 1}"} for k in range(1, 100)]
        plans, slots = plan_parts(defines, reads, 10)
        _execute(self, defines, reads, plans, slots)
        self.assertLessEqual(slots, 2)


class SplitHeaderTest(unittest.TestCase):

    def test_flag_splits_kernels_and_is_recorded(self):
        with tempfile.TemporaryDirectory() as directory:
            subprocess.run([sys.executable, str(REPO / "generate"), "--quiet",
                            str(REPO / "models" / "pendulum.py"), "-o", directory,
                            "--max-function-statements", "4"], check=True)
            text = (Path(directory) / "pendulum.hpp").read_text()
        self.assertIn("regenerate: gencoord generate models/pendulum.py "
                      "--max-function-statements 4", text)
        self.assertIn("#define GENCOORD_NOINLINE", text)
        self.assertIn("GENCOORD_NOINLINE static void mass_matrix_part0(", text)
        self.assertIn("mass_matrix_part0<Scalar>(", text)
        # the checked-in pendulum is short: no parts, no macro
        self.assertNotIn("GENCOORD_NOINLINE", (REPO / "generated" / "pendulum.hpp").read_text())

    def test_large_trees_default_to_shorter_parts(self):
        """A tree that gets looped kernels is cut into parts of 500 statements unless told
        otherwise, which the report says; an explicit size is kept and recorded."""
        chain = str(REPO / "models" / "n_link_chain.py")
        chosen = generate(chain, {"n": "12"}, GenerateOptions(loop_min_nq=10, maximal=True))
        self.assertIn("kernels cut into parts of at most "
                      f"{GenerateOptions.large_tree_part_statements} "
                      "statements", " ".join(chosen.analysis))
        self.assertNotIn("--max-function-statements", chosen.header)
        self.assertIn("GENCOORD_NOINLINE static void", chosen.header)
        # every kernel of the 12-link chain is under 2000 statements: told so, none is cut
        every = GenerateOptions.part_statements
        told = generate(chain, {"n": "12"},
                        GenerateOptions(loop_min_nq=10, maximal=True,
                                        max_part_statements=every))
        self.assertIn(f"--max-function-statements {every}", told.header)
        self.assertNotIn("GENCOORD_NOINLINE static void", told.header)

    def test_negative_sizes_are_refused(self):
        result = subprocess.run([sys.executable, str(REPO / "generate"),
                                 str(REPO / "models" / "pendulum.py"),
                                 "--max-function-statements", "-1"],
                                capture_output=True, text=True)
        self.assertEqual(result.returncode, 2)
        self.assertIn("--max-function-statements must be 0", result.stderr)


if __name__ == "__main__":
    unittest.main()
