# SPDX-License-Identifier: BSD-3-Clause
"""Bad model files: a clear error naming the file, the item (and its line), a non-zero exit,
and an output directory left exactly as it was (no header, no temporary file).

Each bad model is written into a temporary folder by the test; the line a message must name
is the one marked `# <- error` in the source.
"""

from __future__ import annotations

import os
import re
import shutil
import tempfile
import textwrap
import unittest
from pathlib import Path

from .support import (BOB, GENERATED, MARK, MODELS, REPO, describe, marked_line,
                      other_sympy_than_generated, run_generate, snapshot, snapshot_difference)

PREAMBLE = """\
from gencoord import Model, cos, sin
model = Model(dim=2)
theta = model.coordinate("theta", "angle from the downward vertical (rad)")
"""


class BadModelTest(unittest.TestCase):

    def setUp(self):
        self.scratch = tempfile.TemporaryDirectory(prefix="gencoord-bad-")
        root = Path(self.scratch.name)
        self.models = root / "models"
        self.models.mkdir()
        # a populated output folder: real headers plus a stale header of every bad model's
        # name, which a failed run must neither overwrite nor delete
        self.output = root / "out"
        self.output.mkdir()
        for name in ("pendulum.hpp", "double_pendulum.hpp"):
            shutil.copy2(GENERATED / name, self.output / name)

    def tearDown(self):
        self.scratch.cleanup()

    def write_model(self, stem: str, source: str) -> Path:
        path = self.models / f"{stem}.py"
        path.write_text(textwrap.dedent(source), encoding="utf-8")
        (self.output / f"{stem}.hpp").write_text("// an older header: must survive\n",
                                                 encoding="utf-8")
        return path

    def expect_failure(self, model: Path | str, fragments: list[str], line: int | None,
                       *extra: str):
        """Runs ./generate on `model` into the populated output folder and checks the error.

        `fragments` must all appear in stderr (the offending item, the symbol ...); `line`,
        when given, must be reported as `<file>:<line>:`, else the file must still be named.
        """
        output_before = snapshot(self.output)
        models_before = snapshot(self.models)
        result = run_generate(model, "-o", self.output, *extra, timeout=120)
        details = describe(result)
        self.assertNotEqual(result.returncode, 0, f"a bad model was accepted:{details}")
        self.assertNotIn("Traceback", result.stderr,
                         f"a Python traceback instead of a clear message:{details}")
        self.assertIn("error", result.stderr, details)
        if line is not None:
            self.assertIn(f"{model}:{line}:", result.stderr,
                          f"the message must name the file and line {line}:{details}")
        else:
            self.assertIn(str(model), result.stderr, f"the message must name the file:{details}")
        for fragment in fragments:
            self.assertIn(fragment, result.stderr,
                          f"the message must name {fragment!r}:{details}")
        self.assertNotIn("wrote", result.stdout, details)
        changes = snapshot_difference(output_before, snapshot(self.output))
        self.assertEqual(changes, "", f"a failed run changed the output folder:\n{changes}")
        changes = snapshot_difference(models_before, snapshot(self.models))
        self.assertEqual(changes, "", f"a failed run changed the model's folder:\n{changes}")
        return result

    def expect_model_error(self, stem: str, source: str, fragments: list[str],
                           with_line: bool = True):
        source = textwrap.dedent(source)
        line = marked_line(source) if with_line else None
        if with_line:
            self.assertIsNotNone(line, f"test bug: mark the offending line with '{MARK}'")
        return self.expect_failure(self.write_model(stem, source), fragments, line)

    # --- errors the loader reports (while the model file runs) --------------------------------
    def test_python_syntax_error(self):
        self.expect_model_error("syntax_error", PREAMBLE + (
            'bob = model.particle("bob", mass=1, position=[sin(theta), -cos(theta)]  '
            + MARK + "\nmodel.gravity([0, -9.81])\n"), ["syntax"])

    def test_exception_raised_by_the_model_file(self):
        self.expect_model_error("raises", PREAMBLE + (
            "length = 1 / 0  " + MARK + "\n" + BOB), ["ZeroDivisionError"])

    def test_three_components_in_a_2d_model(self):
        self.expect_model_error("three_components", PREAMBLE + (
            'bob = model.particle("bob", mass=1, position=[sin(theta), -cos(theta), 0])  '
            + MARK + "\n"), ["particle 'bob'", "3"])

    def test_gravity_of_the_wrong_size(self):
        self.expect_model_error("gravity_size", PREAMBLE + BOB + (
            "model.gravity([0, 0, -9.81])  " + MARK + "\n"), ["gravity", "3"])

    def test_file_that_does_not_assign_model(self):
        self.expect_model_error("no_model", """\
            from gencoord import Model, cos, sin
            system = Model(dim=2)
            theta = system.coordinate("theta", "angle (rad)")
            bob = system.particle("bob", mass=1, position=[sin(theta), -cos(theta)])
            """, ["'model'"], with_line=False)

    # --- errors the checks report (after the model file ran) ----------------------------------
    # Regression: before commit d2b7185 gencoord/generate/stages.py ran validate(model) without
    # attaching the model file's path, so these errors printed with neither file nor line.
    def test_unknown_symbol_in_a_position(self):
        self.expect_model_error("unknown_symbol", PREAMBLE + (
            "import sympy\n"
            "omega_undeclared = sympy.Symbol('omega_undeclared')\n"
            'bob = model.particle("bob", mass=1, position=[omega_undeclared * sin(theta), '
            "-cos(theta)])  " + MARK + "\n"), ["particle 'bob'", "omega_undeclared"])

    def test_an_input_outside_the_forces(self):
        # an input is a force the caller sets: kinematics, masses and potentials may not use it
        declare = 'u = model.input("u", "a push (N)")\n'
        cases = {
            "input_position": ('bob = model.particle("bob", mass=1, position=[u + sin(theta), '
                               "-cos(theta)])  " + MARK + "\n", ["particle 'bob' position"]),
            "input_mass": ('bob = model.particle("bob", mass=1 + u, position=[sin(theta), '
                           "-cos(theta)])  " + MARK + "\n", ["particle 'bob' mass"]),
            "input_potential": (BOB + "model.force(bob, [u, 0], potential=-u * bob.x[0])  "
                                + MARK + "\n", ["force 'on bob'"]),
            "input_rod": (BOB + 'model.pin(bob, [0, -u])  ' + MARK + "\n",
                          ["pin 'bob'", "anchor"]),
        }
        for stem, (body, fragments) in cases.items():
            with self.subTest(stem):
                self.expect_model_error(stem, PREAMBLE + declare + body,
                                        [*fragments, "input u", "only through forces"])

    def test_undeclared_symbol_in_every_kind_of_item(self):
        # every place a user expression enters: each names the item (and the part of it)
        pivot = 'pivot = model.fixed_point("pivot", [0, 0])\n'
        cases = {
            "rod 'pivot-bob' length": "model.rod(pivot, bob, k_undeclared)",
            "pin 'bob' anchor": "model.pin(bob, [k_undeclared, 0])",
            "plane 'bob' normal": "model.plane(bob, [k_undeclared, 1])",
            "plane 'bob' offset": "model.plane(bob, [0, 1], k_undeclared)",
            "spring 'pivot-bob' stiffness": "model.spring(pivot, bob, k_undeclared, 1)",
            "spring 'pivot-bob' rest length": "model.spring(pivot, bob, 1, k_undeclared)",
            "damper 'pivot-bob'": "model.damper(pivot, bob, k_undeclared)",
            "force 'on bob'": "model.force(bob, [k_undeclared, 0])",
            "generalized force 'on theta' potential":
                "model.generalized_force(theta, 0, potential=k_undeclared)",
            "joint spring on theta": "model.joint_spring(theta, k_undeclared)",
            "gravity": "model.gravity([0, -k_undeclared])",
            "fixed point 'anchor' position": 'model.fixed_point("anchor", [k_undeclared, 0])',
        }
        for item, statement in cases.items():
            with self.subTest(item=item):
                self.expect_model_error("undeclared_" + re.sub(r"\W+", "_", item), PREAMBLE + (
                    "import sympy\nk_undeclared = sympy.Symbol('k_undeclared')\n" + pivot
                    + BOB + statement + "  " + MARK + "\n"), [item, "k_undeclared"])

    def test_undeclared_symbol_in_a_mass(self):
        self.expect_model_error("undeclared_mass", PREAMBLE + (
            "import sympy\n"
            'bob = model.particle("bob", mass=sympy.Symbol("m_undeclared"), '
            "position=[sin(theta), -cos(theta)])  " + MARK + "\n"),
            ["particle 'bob' mass", "m_undeclared"])

    def test_symbol_made_outside_the_model_under_a_declared_name(self):
        self.expect_model_error("lookalike", PREAMBLE + (
            "import sympy\n"
            'l = model.parameter("l", 1.0, "rod length (m)")\n'
            'pivot = model.fixed_point("pivot", [0, 0])\n'
            'bob = model.particle("bob", mass=1, position=[l * sin(theta), -l * cos(theta)])\n'
            'model.rod(pivot, bob, sympy.Symbol("l"))  ' + MARK + "\n"),
            ["rod 'pivot-bob' length", "made outside the model"])

    def test_undefined_function_in_a_position(self):
        self.expect_model_error("undefined_function", PREAMBLE + (
            "import sympy\n"
            'bob = model.particle("bob", mass=1, position=[sympy.Function("f")(theta), '
            "-cos(theta)])  " + MARK + "\n"), ["particle 'bob' position", "f(theta)"])

    def test_coordinate_not_used_in_X(self):
        self.expect_model_error("unused_coordinate", PREAMBLE + (
            'phi = model.coordinate("phi", "never used")  ' + MARK + "\n" + BOB),
            ["coordinate 'phi'"])

    def test_negative_mass(self):
        self.expect_model_error("negative_mass", PREAMBLE + (
            'm = model.parameter("m", -1.0, "mass (kg)")\n'
            'bob = model.particle("bob", mass=m, position=[sin(theta), -cos(theta)])  '
            + MARK + "\n"), ["particle 'bob'", "mass"])

    def test_zero_mass(self):
        self.expect_model_error("zero_mass", PREAMBLE + (
            'bob = model.particle("bob", mass=0, position=[sin(theta), -cos(theta)])  '
            + MARK + "\n"), ["particle 'bob'", "mass"])

    def test_mass_that_depends_on_q(self):
        self.expect_model_error("q_dependent_mass", PREAMBLE + (
            'bob = model.particle("bob", mass=1 + theta**2, position=[sin(theta), '
            "-cos(theta)])  " + MARK + "\n"), ["particle 'bob'", "mass", "theta"])

    def test_parameter_named_like_a_cxx_keyword(self):
        self.expect_model_error("keyword_parameter", PREAMBLE + (
            'length = model.parameter("double", 1.0, "rod length (m)")  ' + MARK + "\n"
            'bob = model.particle("bob", mass=1, position=[length * sin(theta), '
            "-length * cos(theta)])\n"), ["parameter 'double'", "keyword"])

    def test_coordinate_named_like_a_cxx_keyword(self):
        self.expect_model_error("keyword_coordinate", """\
            from gencoord import Model, cos, sin
            model = Model(dim=2)
            angle = model.coordinate("class", "angle (rad)")  # <- error
            bob = model.particle("bob", mass=1, position=[sin(angle), -cos(angle)])
            """, ["coordinate 'class'", "keyword"])

    def test_model_without_coordinates(self):
        self.expect_model_error("no_coordinates", """\
            from gencoord import Model
            model = Model(dim=2)  # <- error
            bob = model.particle("bob", mass=1, position=[0, -1])
            """, ["no coordinates"])

    def test_model_without_particles(self):
        self.expect_model_error("no_particles", """\
            from gencoord import Model
            model = Model(dim=2)  # <- error
            theta = model.coordinate("theta", "angle (rad)")
            """, ["no particles"])

    # --- declared constraints must hold on X; no redundant coordinates ---
    def test_violated_rod_constraint(self):
        self.expect_model_error("violated_rod", PREAMBLE + (
            'l = model.parameter("l", 1.0, "rod length (m)")\n'
            'pivot = model.fixed_point("pivot", [0, 0])\n'
            'bob = model.particle("bob", mass=1, position=[l * sin(theta), -l * cos(theta)])\n'
            "model.rod(pivot, bob, 2 * l)  " + MARK + "\n"), ["rod 'pivot-bob'"])

    def test_rod_of_the_default_length_instead_of_the_parameter(self):
        # holds at the default l = 1 only: the check must sample the parameters too
        self.expect_model_error("literal_rod", PREAMBLE + (
            'l = model.parameter("l", 1.0, "rod length (m)")\n'
            'pivot = model.fixed_point("pivot", [0, 0])\n'
            'bob = model.particle("bob", mass=1, position=[l * sin(theta), -l * cos(theta)])\n'
            "model.rod(pivot, bob, 1.0)  " + MARK + "\n"), ["rod 'pivot-bob'", "l = "])

    def test_redundant_coordinates(self):
        self.expect_model_error("redundant", PREAMBLE + (
            'phi = model.coordinate("phi", "a second angle (rad)")\n'
            'bob = model.particle("bob", mass=1, position=[sin(theta + phi), '
            "-cos(theta + phi)])\n"), ["theta", "phi"], with_line=False)

    def test_redundant_coordinates_of_one_link_deep_in_a_chain(self):
        # a tree is checked joint by joint: the error names the joint's pair alone
        self.expect_model_error("redundant_link", PREAMBLE + (
            'alpha = model.coordinate("alpha", "a second angle (rad)")\n'
            'beta = model.coordinate("beta", "a third angle (rad)")\n'
            'gamma = model.coordinate("gamma", "a fourth angle (rad)")\n'
            "x1, y1 = sin(theta), -cos(theta)\n"
            "x2, y2 = x1 + sin(alpha + beta), y1 - cos(alpha + beta)\n"
            'model.particle("bob1", mass=1, position=[x1, y1])\n'
            'model.particle("bob2", mass=1, position=[x2, y2])\n'
            'model.particle("bob3", mass=1, position=[x2 + sin(gamma), y2 - cos(gamma)])\n'),
            ["the coordinates alpha, beta are redundant", "(alpha: "], with_line=False)

    # --- options -------------------------------------------------------------------------
    def test_set_of_an_unknown_option(self):
        chain = MODELS / "n_link_chain.py"
        self.expect_failure(chain, ["--set", "links", "n"], None, "--set", "links=4")

    def test_set_on_a_model_without_options(self):
        self.expect_failure(MODELS / "pendulum.py", ["--set", "n"], None, "--set", "n=3")

    def test_set_of_a_value_of_the_wrong_type(self):
        chain = MODELS / "n_link_chain.py"
        line = next(number for number, text in
                    enumerate(chain.read_text(encoding="utf-8").splitlines(), start=1)
                    if "model.option(" in text)
        self.expect_failure(chain, ["option 'n'", "abc"], line, "--set", "n=abc")

    def test_set_without_a_value(self):
        result = run_generate(MODELS / "n_link_chain.py", "-o", self.output, "--set", "n")
        self.assertNotEqual(result.returncode, 0, describe(result))
        self.assertIn("key=value", result.stderr, describe(result))


class GoodInvocationTest(unittest.TestCase):

    def test_output_into_a_missing_folder_creates_it(self):
        with tempfile.TemporaryDirectory(prefix="gencoord-new-") as scratch:
            target = Path(scratch) / "a" / "b"
            result = run_generate(MODELS / "pendulum.py", "-o", target, "--quiet",
                                  "--maximal")  # as generated/ is
            self.assertEqual(result.returncode, 0, describe(result))
            self.assertEqual(sorted(p.name for p in target.iterdir()),
                             ["pendulum.hpp", "pendulum.scene.json"],
                             "exactly the header and the scene, no temporary file")
            reason = other_sympy_than_generated(["pendulum.hpp"])
            if reason:
                self.skipTest(reason)
            # the same header but for the banner's regenerate command, which names -o a/b
            written = (target / "pendulum.hpp").read_text(encoding="utf-8").splitlines()
            golden = (GENERATED / "pendulum.hpp").read_text(encoding="utf-8").splitlines()
            self.assertEqual(written[4], golden[4] + f" -o {os.path.relpath(target, REPO)}")
            self.assertEqual(written[:4] + written[5:], golden[:4] + golden[5:])

    def test_help(self):
        result = run_generate("--help")
        self.assertEqual(result.returncode, 0, describe(result))
        self.assertIn("usage", result.stdout.lower(), describe(result))
        self.assertIn("--set", result.stdout, describe(result))

    def test_missing_model_file(self):
        with tempfile.TemporaryDirectory(prefix="gencoord-missing-") as scratch:
            missing = Path(scratch) / "no_such_model.py"
            out = Path(scratch) / "out"
            result = run_generate(missing, "-o", out)
            self.assertNotEqual(result.returncode, 0, describe(result))
            self.assertIn(str(missing), result.stderr, describe(result))
            self.assertNotIn("Traceback", result.stderr, describe(result))
            self.assertFalse(out.exists(), "a failed run created the output folder")


if __name__ == "__main__":
    unittest.main()
