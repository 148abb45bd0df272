# SPDX-License-Identifier: BSD-3-Clause
"""Property tests of the model-file surface: random model files generate headers whose compiled
kernels agree with an independent derivation, and random breakages of them are refused in one
line that names the file (and a line of it), never with a traceback or an "internal error".

A model file here is a 2D or 3D system of one to three coordinates and as many particles: each
particle hangs from the one before on a link or slides along a direction, plus small random
terms of sines, cosines and products of the coordinates; gravity, strain springs and dampers
join random pairs of points. The reference is Lagrange's equations
d/dt dL/dqdot - dL/dq = Q of L = T - V, from the kinetic and potential energies in SymPy, with
the dampers' Q = sum J^T F: nothing of gencoord's derivation is used. The broken files change
one thing of a good one: an argument replaced by junk (a string, None, NaN, a list of the wrong
length, an undefined or wrong-kind name), or a line taken out or repeated.

Run by CTest as `property_tests` (Hypothesis, Debian's python3-hypothesis); the compiled check
needs g++ and Eigen.
"""

from __future__ import annotations

import contextlib
import io
import os
import random
import re
import shutil
import subprocess
import tempfile
import unittest
from pathlib import Path

import mpmath
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gencoord.generate import cli

REPO = Path(__file__).resolve().parents[2]
EIGEN = Path(os.environ.get("EIGEN_INCLUDE_DIR", "/usr/include/eigen3"))
COMPILER = shutil.which("g++")
COMPILED_MODELS = 8
ONE_LINE = re.compile(r"^\S[^\n]*: error: [^\n]+\n?$")


class ModelText:
    """A random model file, with what the reference needs: the SymPy positions, masses and
    forces it declares, over symbols of the same names."""

    def __init__(self, rng: random.Random):
        self.dim = rng.choice([2, 3])
        self.nq = rng.randint(1, 3)
        self.q = [sp.Symbol(f"q{i}") for i in range(self.nq)]
        self.lines = ["from gencoord import Model, cos, sin", "",
                      f"model = Model(dim={self.dim})"]
        for i in range(self.nq):
            initial = round(rng.uniform(-1, 1), 3)
            self.lines.append(f'q{i} = model.coordinate("q{i}", "coordinate {i}", '
                              f"initial={initial})")
        self.masses = [round(rng.uniform(0.5, 2.0), 3) for _ in range(self.nq)]
        self.lengths = [round(rng.uniform(0.5, 1.5), 3) for _ in range(self.nq)]
        for i, length in enumerate(self.lengths):
            self.lines.append(f'l{i} = model.parameter("l{i}", {length}, "length {i} (m)")')
        self.lines.append('o = model.fixed_point("o", [' + ", ".join(["0"] * self.dim) + "])")
        self.positions: list[list[sp.Expr]] = []
        previous = [sp.Integer(0)] * self.dim
        for i in range(self.nq):
            position = [a + b for a, b in zip(previous, self._step(rng, i))]
            self.positions.append(position)
            text = ", ".join(sp.sstr(c) for c in position)
            self.lines.append(f'p{i} = model.particle("p{i}", mass={self.masses[i]}, '
                              f"position=[{text}])")
            previous = position
        self.gravity = [round(rng.uniform(-10, 10), 2) for _ in range(self.dim)]
        self.lines.append(f"model.gravity({self.gravity})")
        points = ["o"] + [f"p{i}" for i in range(self.nq)]
        self.springs, self.dampers = [], []
        for _ in range(rng.randint(0, 2)):
            a, b = rng.sample(points, 2)
            k, rest = round(rng.uniform(1, 20), 2), round(rng.uniform(0.3, 2), 2)
            self.springs.append((a, b, k, rest))
            self.lines.append(f"model.spring({a}, {b}, {k}, {rest})")
        for _ in range(rng.randint(0, 1)):
            a, b = rng.sample(points, 2)
            c = round(rng.uniform(0.1, 2), 2)
            self.dampers.append((a, b, c))
            self.lines.append(f"model.damper({a}, {b}, {c})")
        self.state = ([round(rng.uniform(-1, 1), 3) for _ in range(self.nq)],
                      [round(rng.uniform(-1, 1), 3) for _ in range(self.nq)])

    def _step(self, rng: random.Random, i: int) -> list[sp.Expr]:
        """The offset of particle i from the one before: a link swinging in q_i, or a slide
        along a direction, plus small smooth terms in all the coordinates."""
        q, length = self.q[i], sp.Symbol(f"l{i}")
        if rng.random() < 0.7:
            step = [length * sp.sin(q), -length * sp.cos(q)]
        else:
            angle = rng.uniform(0, 3)
            step = [q * round(float(sp.cos(angle)), 3), q * round(float(sp.sin(angle)), 3)]
        step += [sp.Integer(0)] * (self.dim - 2)
        for axis in range(self.dim):
            if rng.random() < 0.4:
                other = rng.choice(self.q)
                term = rng.choice([sp.sin(other), sp.cos(other), other * q, other ** 2])
                step[axis] += sp.Rational(rng.randint(-3, 3), 10) * term
        if self.dim == 3 and rng.random() < 0.5:
            step[2] += sp.Rational(rng.randint(1, 5), 10) * sp.sin(q + rng.choice(self.q))
        return step

    @property
    def text(self) -> str:
        return "\n".join(self.lines) + "\n"

    def point(self, name: str) -> list[sp.Expr]:
        return [sp.Integer(0)] * self.dim if name == "o" else self.positions[int(name[1:])]

    def reference_qddot(self) -> list[mpmath.mpf]:
        """qddot at self.state from Lagrange's equations, in 30-digit arithmetic."""
        qdot = [sp.Symbol(f"qdot{i}") for i in range(self.nq)]
        values = {sp.Symbol(f"l{i}"): sp.Float(l, 30) for i, l in enumerate(self.lengths)}
        q0, v0 = self.state
        values.update({s: sp.Float(x, 30) for s, x in zip(self.q, q0)})
        values.update({s: sp.Float(x, 30) for s, x in zip(qdot, v0)})

        def velocity(position):
            return [sum(sp.diff(c, s) * d for s, d in zip(self.q, qdot)) for c in position]

        kinetic = sum(m * sum(c ** 2 for c in velocity(x)) / 2
                      for m, x in zip(self.masses, self.positions))
        potential = -sum(m * sum(g * c for g, c in zip(self.gravity, x))
                         for m, x in zip(self.masses, self.positions))
        for a, b, k, rest in self.springs:
            d = [xb - xa for xa, xb in zip(self.point(a), self.point(b))]
            potential += k * (sp.sqrt(sum(c ** 2 for c in d)) - rest) ** 2 / (2 * rest)
        generalized = [sp.Integer(0)] * self.nq
        for a, b, c in self.dampers:
            va, vb = velocity(self.point(a)), velocity(self.point(b))
            relative = [y - x for x, y in zip(va, vb)]
            for name, sign in ((a, 1), (b, -1)):  # c (v_b - v_a) on a, its opposite on b
                x = self.point(name)
                for j, s in enumerate(self.q):
                    generalized[j] += sum(sign * c * r * sp.diff(xc, s)
                                          for r, xc in zip(relative, x))
        lagrangian = kinetic - potential
        momenta = [sp.diff(lagrangian, d) for d in qdot]
        mass = sp.Matrix(self.nq, self.nq, lambda r, c: sp.diff(momenta[r], qdot[c]))
        rest_terms = sp.Matrix([sp.diff(lagrangian, self.q[r]) + generalized[r]
                                - sum(sp.diff(momenta[r], s) * d for s, d in zip(self.q, qdot))
                                for r in range(self.nq)])
        with mpmath.workdps(30):
            m = mpmath.matrix([[mpmath.mpf(str(sp.N(mass[r, c].subs(values), 30)))
                                for c in range(self.nq)] for r in range(self.nq)])
            f = mpmath.matrix([mpmath.mpf(str(sp.N(rest_terms[r].subs(values), 30)))
                               for r in range(self.nq)])
            return list(mpmath.lu_solve(m, f))


def generate(model: Path, output: Path) -> tuple[int, str]:
    """(exit status, stderr) of `generate model -o output --quiet`, in this process."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = cli.main([str(model), "-o", str(output), "--quiet"])
    return status, err.getvalue()


class ModelFileTest(unittest.TestCase):

    def setUp(self):
        scratch = tempfile.TemporaryDirectory(prefix="gencoord-model-fuzz-")
        self.addCleanup(scratch.cleanup)
        self.root = Path(scratch.name)

    @unittest.skipUnless(COMPILER and (EIGEN / "Eigen" / "Core").exists(), "needs g++ and Eigen")
    def test_random_models_compile_and_agree_with_lagranges_equations(self):
        models = [ModelText(random.Random(seed)) for seed in range(COMPILED_MODELS)]
        calls = []
        for k, model in enumerate(models):
            path = self.root / f"random_{k}.py"
            path.write_text(model.text, encoding="utf-8")
            status, err = generate(path, self.root / "generated")
            self.assertEqual(status, 0, f"{err}\n{model.text}")
            q, v = model.state
            struct = f"gencoord::models::Random{k}"
            calls.append(f"  {{ {struct}::QVector<double> q; q << {', '.join(map(str, q))};\n"
                         f"    {struct}::VVector<double> v; v << {', '.join(map(str, v))};\n"
                         f"    const auto a = {struct}::qddot(q, v, 0.0, {struct}::Params{{}});\n"
                         f"    for (int i = 0; i < a.size(); ++i) std::printf(\"%d %.17g\\n\", "
                         f"{k}, a[i]); }}")
        program = self.root / "check.cpp"
        program.write_text("#include <cstdio>\n"
                           + "".join(f'#include "generated/random_{k}.hpp"\n'
                                     for k in range(len(models)))
                           + "int main() {\n" + "\n".join(calls) + "\n}\n", encoding="utf-8")
        build = subprocess.run([COMPILER, "-std=c++17", "-O1", "-Wall", "-Wextra", "-Werror",
                                f"-I{self.root}", f"-I{EIGEN}", str(program), "-o",
                                str(self.root / "check")], capture_output=True, text=True,
                               timeout=600)
        self.assertEqual(build.returncode, 0, build.stderr[-3000:])
        run = subprocess.run([str(self.root / "check")], capture_output=True, text=True,
                             check=True, timeout=60)
        values: dict[int, list[float]] = {}
        for line in run.stdout.splitlines():
            k, value = line.split()
            values.setdefault(int(k), []).append(float(value))
        for k, model in enumerate(models):
            with self.subTest(model=k):
                expected = model.reference_qddot()
                scale = max(1.0, max(abs(float(e)) for e in expected))
                for got, want in zip(values[k], expected):
                    self.assertLess(abs(got - float(want)) / scale, 1e-9,
                                    f"{values[k]} vs {expected}\n{model.text}")

    @settings(max_examples=120, deadline=None, derandomize=True,
              suppress_health_check=[HealthCheck.too_slow])
    @given(st.randoms(use_true_random=False), st.data())
    def test_a_broken_model_file_is_one_line_naming_it(self, rng, data):
        model = ModelText(rng)
        lines = model.lines[:]
        at = data.draw(st.integers(min_value=2, max_value=len(lines) - 1))
        how = data.draw(st.sampled_from(["argument", "argument", "argument", "remove",
                                         "repeat"]))
        if how == "remove":
            del lines[at]
        elif how == "repeat":
            lines.insert(at, lines[at])
        else:
            arguments = [m.span() for m in re.finditer(r"(?<=[(,\[=]) ?[^,()\[\]=]+(?=[,)\]])",
                                                       lines[at])]
            if arguments:
                start, end = data.draw(st.sampled_from(arguments))
                junk = data.draw(st.sampled_from([
                    "None", "'x'", "float('nan')", "float('inf')", "[1, 2, 3, 4]", "[]",
                    "undefined_name", "-1", "0", "1e400", "model", "o", "p0", "q0", "sin",
                    "'p0'", "(1, 2)", "{}", "1j", "True"]))
                lines[at] = lines[at][:start] + " " + junk + lines[at][end:]
        path = self.root / "broken.py"
        path.write_text("\n".join(lines) + "\n", encoding="utf-8")
        status, err = generate(path, self.root / "out")
        if status == 0:
            return  # the change kept a valid model (a junk number where any number goes)
        self.assertEqual(status, 1, err)
        self.assertRegex(err, ONE_LINE, "\n".join(lines))
        self.assertTrue(err.startswith(str(path)), err)
        self.assertNotIn("internal error", err, "\n".join(lines))
        self.assertNotIn("Traceback", err)


if __name__ == "__main__":
    unittest.main()
