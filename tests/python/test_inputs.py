# SPDX-License-Identifier: BSD-3-Clause
"""Control inputs (model.input): they are fields of Params, the input matrix B = dFt/du is
their generalized force, and the header names them.

Where they may appear is tested with the other bad models (test_bad_models.py); the values
of B and of the linearization are tested against the C++ runtime and an independent Kane
derivation with the Python modules (tests/python_module/test_control.py).
"""

from __future__ import annotations

import re
import tempfile
import textwrap
import unittest
from pathlib import Path

import sympy as sp

from gencoord.derive.dense import derive
from gencoord.generate.load import load_model
from gencoord.generate.stages import generate

PUSHED_PENDULUM = """\
from gencoord import Model, cos, sin
model = Model(dim=2)
theta = model.coordinate("theta", "angle from the downward vertical (rad)")
l = model.parameter("l", 0.8, "length (m)")
push = model.input("push", "horizontal force on the bob (N)")
tau = model.input("tau", "torque at the pivot (N m)")
bob = model.particle("bob", mass=1, position=[l * sin(theta), -l * cos(theta)])
model.gravity([0, -9.81])
model.force(bob, [push, 0])
model.generalized_force(theta, tau)
"""


class InputTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.scratch = tempfile.TemporaryDirectory(prefix="gencoord-inputs-")
        cls.path = Path(cls.scratch.name) / "pushed_pendulum.py"
        cls.path.write_text(textwrap.dedent(PUSHED_PENDULUM), encoding="utf-8")
        cls.model, _, _ = load_model(str(cls.path), None)

    @classmethod
    def tearDownClass(cls):
        cls.scratch.cleanup()

    def test_inputs_are_parameters_of_kind_input(self):
        self.assertEqual([p.name for p in self.model.inputs], ["push", "tau"])
        self.assertEqual([p.name for p in self.model.parameters], ["l", "push", "tau"])
        self.assertEqual([p.default for p in self.model.inputs], [0.0, 0.0])
        self.assertEqual(self.model.inputs[0].label(), "input 'push'")

    def test_the_input_matrix_is_the_generalized_force_per_unit_input(self):
        d = derive(self.model)
        theta, l = sp.Symbol("theta", real=True), sp.Symbol("l", real=True)
        B = d.applied_forces.jacobian(d.inputs)
        # a horizontal force at the bob: J^T (1, 0) = l cos(theta); the torque acts on theta
        self.assertEqual(sp.simplify(B - sp.Matrix([[l * sp.cos(theta), 1]])),
                         sp.zeros(1, 2))

    def test_the_header_names_the_inputs_and_emits_input_matrix(self):
        header = generate(str(self.path)).header
        self.assertIn("static constexpr int num_inputs = 2;", header)
        self.assertIn('input_names{{"push", "tau"}}', header)
        self.assertIn("double push = 0.0;", header)
        self.assertIn("std::array<double, 2> inputs() const { return {{push, tau}}; }", header)
        self.assertRegex(header, r"static InputMatrix<Scalar> input_matrix\(")
        body = header[header.index("input_matrix("):]
        body = body[:body.index("return result;")]
        self.assertEqual(len(re.findall(r"result\(0, [01]\) =", body)), 2)

    def test_a_model_without_inputs_says_so(self):
        path = Path(self.scratch.name) / "plain_pendulum.py"
        path.write_text(textwrap.dedent(PUSHED_PENDULUM).replace(
            'push = model.input("push", "horizontal force on the bob (N)")', "push = 0").replace(
            'tau = model.input("tau", "torque at the pivot (N m)")', "tau = 0"),
            encoding="utf-8")
        header = generate(str(path)).header
        self.assertIn("static constexpr int num_inputs = 0;", header)
        self.assertNotIn("input_matrix(", header)
        self.assertIn("std::array<double, 0> inputs() const { return {{}}; }", header)


if __name__ == "__main__":
    unittest.main()
