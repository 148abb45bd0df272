# SPDX-License-Identifier: BSD-3-Clause
"""No header that passed the generator fails to compile: the accepted cases of
refused_cases.ACCEPTED (names next to reserved ones, functions smooth where defined) are
generated and compiled (g++ -fsyntax-only, every kernel instantiated for double); and every
macro the compiler defines is one the generator refuses as a name."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import tempfile
import textwrap
import unittest
from pathlib import Path

from gencoord.naming import type_name
from gencoord.cxx.reserved_names import name_problem

from . import refused_cases
from .support import REPO
from .test_refused_inputs import run_cli

EIGEN = Path(os.environ.get("EIGEN_INCLUDE_DIR", "/usr/include/eigen3"))
COMPILER = shutil.which("g++")
_KERNEL = re.compile(r"template <typename Scalar>\n\s*static [^;{]*?\b(\w+)\(")


def instantiations(header: str, struct: str) -> list[str]:
    """A statement taking the address of each kernel of `struct` (and of its Maximal) for
    double, which makes the compiler instantiate every kernel body."""
    nested = header.index("struct Maximal {")
    return [f"  (void)&gencoord::models::{struct}{'::Maximal' if m.start() > nested else ''}"
            f"::template {m.group(1)}<double>;" for m in _KERNEL.finditer(header)]


@unittest.skipUnless(COMPILER and (EIGEN / "Eigen" / "Core").exists(), "needs g++ and Eigen")
class AcceptedHeadersCompileTest(unittest.TestCase):

    def test_accepted_models_compile(self):
        with tempfile.TemporaryDirectory(prefix="gencoord-clash-") as scratch:
            root = Path(scratch)
            for stem, source in refused_cases.ACCEPTED.items():
                with self.subTest(case=stem):
                    model = root / f"{stem}.py"
                    model.write_text(textwrap.dedent(source), encoding="utf-8")
                    status, _, err = run_cli(model, "-o", root / "generated", "--quiet",
                                             "--maximal")
                    self.assertEqual(status, 0, err)
                    header = (root / "generated" / f"{stem}.hpp").read_text(encoding="utf-8")
                    use = root / f"{stem}.cpp"
                    use.write_text(f'#include "generated/{stem}.hpp"\nvoid use() {{\n'
                                   + "\n".join(instantiations(header, type_name(stem)))
                                   + "\n}\n", encoding="utf-8")
                    # gnu++17: the dialect CMake uses by default, where `linux` is a macro
                    result = subprocess.run(
                        [COMPILER, "-std=gnu++17", "-fsyntax-only", f"-I{root}",
                         f"-I{REPO / 'runtime' / 'include'}", f"-I{EIGEN}", str(use)],
                        capture_output=True, text=True, timeout=600)
                    self.assertEqual(result.returncode, 0, result.stderr[-3000:])


@unittest.skipUnless(COMPILER, "needs g++")
class MacroListTest(unittest.TestCase):

    def test_every_macro_the_compiler_defines_is_refused(self):
        result = subprocess.run([str(REPO / "scripts" / "list_cxx_macros.sh"), COMPILER],
                                capture_output=True, text=True, timeout=300)
        self.assertEqual(result.returncode, 0, result.stderr)
        accepted = [name for name in result.stdout.split() if name_problem(name) is None]
        self.assertEqual(accepted, [], "macros this compiler defines that a model may use as "
                         "names: add them to gencoord/cxx/cxx_macros.txt")


if __name__ == "__main__":
    unittest.main()
