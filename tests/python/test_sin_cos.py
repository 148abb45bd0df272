# SPDX-License-Identifier: BSD-3-Clause
"""Kernels take the sines and cosines of their coordinates in one call (gencoord/cxx/sin_cos.py):
which calls are batched, what the code reads instead, and a header that uses it."""

from __future__ import annotations

import re
import unittest

from gencoord.cxx.sin_cos import MIN_ARGUMENTS, batch_sin_cos
from gencoord.generate.stages import generate

from .support import MODELS


class BatchSinCosTest(unittest.TestCase):
    def test_sines_and_cosines_of_coordinates_read_the_batch(self):
        arguments, codes = batch_sin_cos(
            ["q0", "q1", "q2"], ["cos(q2)", "l*sin(q0) + sin(q2)*Scalar(2.0)", "q1*v0"])
        self.assertEqual(arguments, ["q0", "q2"])  # coordinate order; q1 has none
        self.assertEqual(codes, ["cos_of[1]", "l*sin_of[0] + sin_of[1]*Scalar(2.0)", "q1*v0"])

    def test_other_arguments_and_functions_are_left_alone(self):
        codes = ["sin(q0 + q1)", "asin(q0)", "sin(t)", "std::sin(q0)", "sinh(q1)", "cos(q01)",
                 "sin(q0)", "cos(q1)"]
        arguments, batched = batch_sin_cos(["q0", "q1"], codes)
        self.assertEqual(arguments, ["q0", "q1"])
        self.assertEqual(batched[:6], codes[:6])
        self.assertEqual(batched[6:], ["sin_of[0]", "cos_of[1]"])

    def test_fewer_than_the_minimum_stay_calls(self):
        fewer = [f"q{k}" for k in range(MIN_ARGUMENTS - 1)]
        codes = [f"sin({name})*cos({name})" for name in fewer] + ["sin(q8 + q9)"]
        self.assertEqual(batch_sin_cos(fewer + ["q8", "q9"], codes), ([], codes))
        enough = fewer + ["q8"]
        self.assertEqual(batch_sin_cos(enough, codes + ["cos(q8)"])[0], enough)


class HeaderTest(unittest.TestCase):
    def test_a_double_pendulum_reads_both_angles_from_one_call(self):
        header = generate(str(MODELS / "double_pendulum.py")).header
        self.assertIn("namespace gencoord_kernel_math", header)
        self.assertIn("const Scalar sin_cos_of[2] = {theta1, theta2};", header)
        # every kernel reading the angles has them from the batch, none calls sin or cos
        code = header[header.index("struct DoublePendulum"):]  # after the docstring
        self.assertIsNone(re.search(r"\b(sin|cos)\(theta[12]\)", code))
        self.assertIn("sin_of[1]", header)

    def test_a_model_without_two_angles_has_no_helper(self):
        header = generate(str(MODELS / "pendulum.py")).header
        self.assertNotIn("gencoord_kernel_math", header)
        self.assertIn("sin(theta)", header)


if __name__ == "__main__":
    unittest.main()
