# SPDX-License-Identifier: BSD-3-Clause
"""The structured derivation (named intermediates, grouped sums) against the plain one.

gencoord/derive/structured.py rewrites every output in terms of intermediates so large models
generate fast; this checks, at random states in extended precision, that each output still
has the value derive/dense.py's flat expressions give. The C++ reference
values test checks the same end to end, after CSE and printing.
"""

from __future__ import annotations

import random
import unittest

import mpmath
import sympy as sp

from gencoord.derive.dense import Kinematics, derive
from gencoord.generate.load import load_model
from gencoord.derive.structured import derive_structured

from .support import DIGITS, MODELS, relative_error

FIELDS = ["positions", "velocities", "jacobian", "bias_acceleration", "mass_matrix",
          "applied_forces", "inertial_forces", "generalized_forces", "kinetic_energy",
          "potential_energy", "generalized_potential", "linear_momentum", "angular_momentum"]
CASES = [("n_link_chain.py", {"n": "6"}), ("falling_cat.py", None),
         ("rigid_body_euler.py", None), ("spring_pendulum.py", None),
         ("stiff_chain.py", {"n": "4"}), ("pendulum_3d.py", None)]
STATES = 3


def _values(field, derivation) -> list[sp.Expr]:
    value = getattr(derivation, field)
    return list(value) if isinstance(value, sp.MatrixBase) else [value]


def _number(value: sp.Expr) -> mpmath.mpc:
    """A value as an mpmath number at full precision. The inputs are random, so a body's
    inertia tensor need not be physical and its point masses can sit at complex offsets; the
    two derivations are equal as algebra all the same."""
    real, imaginary = value.as_real_imag()
    return mpmath.mpc(mpmath.mpf(real), mpmath.mpf(imaginary))


class StructuredDerivationTest(unittest.TestCase):

    def test_outputs_match_the_plain_derivation(self):
        for model_file, options in CASES:
            model, name, _ = load_model(str(MODELS / model_file), options)
            kin = Kinematics(model)
            plain = derive(model, kin)
            structured, definitions = derive_structured(model, kin)
            inputs = [*plain.q, *plain.v, *plain.params, plain.t]
            rng = random.Random(name)
            with mpmath.workdps(DIGITS):
                for _ in range(STATES):
                    point = {s: sp.Float(rng.uniform(0.3, 2.0), DIGITS) for s in inputs}
                    for symbol, expr in definitions:  # run the intermediates in order
                        point[symbol] = expr.xreplace(point).evalf(DIGITS)
                    for field in FIELDS:
                        expected = [e.xreplace(point).evalf(DIGITS)
                                    for e in _values(field, plain)]
                        actual = [e.xreplace(point).evalf(DIGITS)
                                  for e in _values(field, structured)]
                        error = relative_error([_number(x) for x in actual],
                                               [_number(x) for x in expected])
                        self.assertLess(error, mpmath.mpf(10) ** (8 - DIGITS),
                                        f"{name}: {field} differs ({error})")


if __name__ == "__main__":
    unittest.main()
