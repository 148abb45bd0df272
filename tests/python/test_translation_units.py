# SPDX-License-Identifier: BSD-3-Clause
"""--translation-units N: every kernel's parts compiled for double in N files of their own.

The header declares each part group `extern template`; <name>_double_<k>.cpp instantiates
group k and, defining GENCOORD_PART_GROUP k, sees only group k's definitions. Checked
here: the groups are deterministic, group 0 holds the kernels off the derivative path (which
CMake compiles with other scheduling) and the other groups are balanced, every part is in
exactly one file and inside its group's guard, stale files of an earlier run are removed, and
(with g++ and nm) a file that includes the header and calls every kernel compiles no part for
double itself but leaves them to the group files, which define each exactly once.
tests/models/translation_units_test.cc checks that the linked program computes what the
header-only kernels compute.
"""

from __future__ import annotations

import random
import re
import shutil
import subprocess
import tempfile
import unittest
from pathlib import Path

from gencoord.optimize.split import (assign_groups, assign_role_groups, is_derivative_path,
                                     plan_parts)

from .support import describe, run_generate

EIGEN = Path("/usr/include/eigen3")


class GroupAssignmentTest(unittest.TestCase):

    def test_groups_are_balanced_and_deterministic(self):
        rng = random.Random(5)
        for _ in range(200):
            sizes = [rng.randint(1, 3000) for _ in range(rng.randint(0, 40))]
            groups = rng.randint(1, 6)
            group_of = assign_groups(sizes, groups)
            self.assertEqual(group_of, assign_groups(sizes, groups))
            self.assertTrue(all(0 <= g < groups for g in group_of))
            load = [0] * groups
            for size, g in zip(sizes, group_of):
                load[g] += size
            # greedy largest-first: no group exceeds the mean by more than the largest part
            if sizes:
                self.assertLessEqual(max(load), sum(sizes) / groups + max(sizes),
                                     (sizes, groups, load))

    def test_derivative_path_is_kept_out_of_group_zero(self):
        self.assertTrue(all(map(is_derivative_path, ("dynamics", "residual_jacobians",
                                                     "jacobian", "force_jacobian_x"))))
        self.assertFalse(any(map(is_derivative_path, ("qddot", "inverse_dynamics",
                                                      "mass_matrix", "forces"))))
        rng = random.Random(7)
        for _ in range(200):
            count = rng.randint(0, 30)
            sizes = [rng.randint(1, 3000) for _ in range(count)]
            on_path = [rng.random() < 0.4 for _ in range(count)]
            groups = rng.randint(1, 5)
            group_of = assign_role_groups(sizes, on_path, groups)
            self.assertEqual(group_of, assign_role_groups(sizes, on_path, groups))
            if groups == 1:
                self.assertEqual(group_of, [0] * count)
                continue
            for path, group in zip(on_path, group_of):
                self.assertEqual(group == 0, not path, (on_path, group_of))
            self.assertTrue(all(g < groups for g in group_of))
            # the derivative path balanced over groups 1 and up as assign_groups balances
            apart = [k for k in range(count) if on_path[k]]
            self.assertEqual([group_of[k] - 1 for k in apart],
                             assign_groups([sizes[k] for k in apart], groups - 1))

    def test_always_makes_one_part_of_a_short_kernel(self):
        defines = ["t0", "t1", None]
        reads = [set(), {"t0"}, {"t1"}]
        self.assertEqual(plan_parts(defines, reads, 2000), ([], 0))
        plans, slots = plan_parts(defines, reads, 2000, always=True)
        self.assertEqual((len(plans), slots), (1, 0))
        self.assertEqual(sorted(plans[0].statements), [0, 1, 2])
        self.assertEqual((plans[0].loads, plans[0].stores), ({}, {}))
        self.assertEqual(plan_parts([], [], 2000, always=True), ([], 0))
        # with max 0 (never split) a kernel is still one part
        self.assertEqual(len(plan_parts(defines, reads, 0, always=True)[0]), 1)


class TranslationUnitsTest(unittest.TestCase):

    def setUp(self):
        self.scratch = tempfile.TemporaryDirectory(prefix="gencoord-tu-")
        self.output = Path(self.scratch.name)

    def tearDown(self):
        self.scratch.cleanup()

    def generate(self, *arguments: str):
        result = run_generate("models/double_pendulum.py", "--quiet", "-o", self.output,
                              *arguments)
        self.assertEqual(result.returncode, 0, describe(result))
        return {p.name: p.read_text(encoding="utf-8") for p in sorted(self.output.iterdir())
                if not p.name.endswith(".scene.json")}  # the scene: test_scene.py

    def test_files_parts_and_extern_declarations(self):
        files = self.generate("--translation-units", "3", "--max-function-statements", "40")
        self.assertEqual(sorted(files), ["double_pendulum.hpp", "double_pendulum_double_0.cpp",
                                         "double_pendulum_double_1.cpp",
                                         "double_pendulum_double_2.cpp"])
        header = files["double_pendulum.hpp"]
        self.assertIn("regenerate: gencoord generate models/double_pendulum.py "
                      "--max-function-statements 40 --translation-units 3", header)
        declared = set(re.findall(r"^extern template struct (\S+)<double>;$", header, re.M))
        instantiated = set()
        for group in range(3):
            source = files[f"double_pendulum_double_{group}.cpp"]
            self.assertIn('#include "double_pendulum.hpp"', source)
            mine = re.findall(r"^template struct (\S+)<double>;$", source, re.M)
            self.assertTrue(mine, f"group {group} instantiates nothing:\n{source}")
            self.assertTrue(all(name.endswith(f"::Parts{group}") for name in mine), mine)
            instantiated.update(mine)
        self.assertEqual(declared, instantiated)
        # every kernel calls its parts through a group; none is defined in a class body
        calls = re.findall(r"^ +Parts(\d)<Scalar>::(\w+_part\d+)\(", header, re.M)
        defined = re.findall(r"^void (?:\w+::)+Parts(\d)<Scalar>::(\w+_part\d+)\(", header, re.M)
        self.assertTrue(calls)
        self.assertEqual(sorted(calls), sorted(defined))
        self.assertNotIn("template <typename Scalar>\n  GENCOORD_NOINLINE", header)
        # group k's file sees only group k's definitions (GENCOORD_PART_GROUP); every
        # definition is inside the guard of its own group
        guarded = re.findall(r"^#if !defined\(GENCOORD_PART_GROUP\) \|\| GENCOORD_PART_GROUP == "
                             r"(\d)\n(.*?)^#endif  // GENCOORD_PART_GROUP (\d)$", header,
                             re.M | re.S)
        self.assertTrue(guarded)
        inside = []
        for group, body, closing in guarded:
            self.assertEqual(group, closing)
            found = re.findall(r"^void (?:\w+::)+Parts(\d)<Scalar>::(\w+_part\d+)\(", body, re.M)
            self.assertTrue(all(g == group for g, _ in found), (group, found))
            inside += found
        self.assertEqual(sorted(inside), sorted(defined))
        for group in range(3):
            self.assertIn(f'#define GENCOORD_PART_GROUP {group}  // the header defines only this '
                          f'group\'s parts here\n#include "double_pendulum.hpp"',
                          files[f"double_pendulum_double_{group}.cpp"])
        self.assertEqual(files, self.generate("--translation-units", "3",
                                              "--max-function-statements", "40"),
                         "a second generation wrote different files")

    def test_stale_group_files_are_removed(self):
        self.generate("--translation-units", "3")
        keep = self.output / "double_pendulum_double_notes.cpp"  # not a group file: kept
        keep.write_text("// mine\n", encoding="utf-8")
        self.assertEqual(sorted(self.generate("--translation-units", "1")),
                         ["double_pendulum.hpp", "double_pendulum_double_0.cpp",
                          "double_pendulum_double_notes.cpp"])
        files = self.generate()
        self.assertEqual(sorted(files), ["double_pendulum.hpp",
                                         "double_pendulum_double_notes.cpp"])
        self.assertNotIn("extern template", files["double_pendulum.hpp"])

    def test_negative_count_is_refused(self):
        result = run_generate("models/double_pendulum.py", "-o", self.output,
                              "--translation-units", "-1")
        self.assertEqual(result.returncode, 2, describe(result))
        self.assertIn("--translation-units", result.stderr)
        self.assertEqual(list(self.output.iterdir()), [])

    @unittest.skipUnless(shutil.which("g++") and shutil.which("nm") and EIGEN.is_dir(),
                         "needs g++, nm and Eigen")
    def test_including_file_compiles_no_part_for_double(self):
        self.generate("--translation-units", "2", "--max-function-statements", "40",
                      "--maximal")
        user = self.output / "user.cpp"
        user.write_text(
            '#include "double_pendulum.hpp"\n'
            "using M = gencoord::models::DoublePendulum;\n"
            "double f(const M::QVector<double>& q, const M::QVector<double>& v,\n"
            "         const M::Params& p) {\n"
            "  M::QMatrix<double> a, b;\n"
            "  M::residual_jacobians(q, v, q, 0.0, p, &a, &b);\n"
            "  const M::XVector<double> x = M::positions(q, 0.0, p);\n"
            "  return M::qddot(q, v, 0.0, p).sum() + a.sum() + b.sum() +\n"
            "         M::Maximal::force_jacobian_x(x, x, 0.0, 1e4, 1.0, p)[0] +\n"
            "         M::qddot<float>(q.cast<float>(), v.cast<float>(), 0.0f, p).sum();\n"
            "}\n", encoding="utf-8")
        symbols = {}
        for name in ("user", "double_pendulum_double_0", "double_pendulum_double_1"):
            compiled = subprocess.run(
                ["g++", "-std=c++17", "-O2", "-Wall", "-Wextra", "-Werror", f"-I{EIGEN}",
                 "-c", f"{name}.cpp", "-o", f"{name}.o"],
                cwd=self.output, capture_output=True, text=True)
            self.assertEqual(compiled.returncode, 0, compiled.stderr)
            listed = subprocess.run(["nm", "-C", f"{name}.o"], cwd=self.output,
                                    capture_output=True, text=True, check=True)
            symbols[name] = [re.match(r"\s*(?:[0-9a-f]+ )?(\w) (.*)", line).groups()
                             for line in listed.stdout.splitlines() if "_part" in line]
        user_double = [s for s in symbols["user"] if "<double>" in s[1]]
        self.assertTrue(user_double)
        self.assertTrue(all(kind == "U" for kind, _ in user_double),
                        f"user.cpp compiled parts for double: {user_double}")
        self.assertTrue(any("<float>" in name and kind != "U" for kind, name in symbols["user"]),
                        "float parts should be compiled where they are used")
        defined = [name for group in ("double_pendulum_double_0", "double_pendulum_double_1")
                   for kind, name in symbols[group] if kind != "U"]
        self.assertEqual(len(defined), len(set(defined)), "a part defined in two files")
        self.assertLessEqual({name for _, name in user_double}, set(defined))


if __name__ == "__main__":
    unittest.main()
