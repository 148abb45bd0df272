# SPDX-License-Identifier: BSD-3-Clause
"""Model options reach Model.option explicitly: from the constructor, or from the options
the loader requests while it runs a model file, and from nowhere else."""

from __future__ import annotations

import unittest

from gencoord.errors import ModelError
from gencoord.generate.load import load_model
from gencoord.dsl.build_options import REQUESTED_OPTIONS, requesting_options
from gencoord.dsl.model import Model
from gencoord.naming import model_name

from .support import MODELS


class ModelOptionsTest(unittest.TestCase):
    def test_default_without_a_request(self):
        self.assertEqual(Model(dim=2).option("n", 3, "links"), 3)

    def test_constructor_options_are_converted_to_the_default_type(self):
        model = Model(dim=2, options={"n": "7", "L": "2.5"})
        self.assertEqual(model.option("n", 3, "links"), 7)
        self.assertEqual(model.option("L", 1.0, "length"), 2.5)
        self.assertEqual(model.options, {"n": 7, "L": 2.5})

    def test_a_value_of_the_wrong_type_is_refused(self):
        with self.assertRaisesRegex(ModelError, "n=many is not a int"):
            Model(dim=2, options={"n": "many"}).option("n", 3, "links")

    def test_a_value_outside_the_declared_range_is_refused_with_the_range(self):
        with self.assertRaisesRegex(ModelError, r"n=0 is outside the option's range >= 1"):
            Model(dim=2, options={"n": "0"}).option("n", 3, "links", minimum=1)
        with self.assertRaisesRegex(ModelError, r"L=9.5 is outside .* \[0.5, 2\] \(length\)"):
            Model(dim=2, options={"L": "9.5"}).option("L", 1.0, "length", minimum=0.5, maximum=2)
        with self.assertRaisesRegex(ModelError, r"n=-3 is outside the option's range >= 1"):
            load_model(str(MODELS / "n_link_chain.py"), {"n": "-3"})

    def test_a_negative_value_names_the_model_with_m_for_the_sign(self):
        self.assertEqual(model_name("models/bar.py", {"scale": -1.5}), "bar_m1_5")

    def test_requested_options_hold_only_inside_the_block(self):
        with requesting_options({"n": "4"}):
            inside = Model(dim=2)
        self.assertEqual(inside.option("n", 3, "links"), 4)
        self.assertEqual(Model(dim=2).option("n", 3, "links"), 3)
        self.assertEqual(dict(REQUESTED_OPTIONS.get()), {})

    def test_constructor_options_win_over_requested_ones(self):
        with requesting_options({"n": "4"}):
            model = Model(dim=2, options={})
        self.assertEqual(model.option("n", 3, "links"), 3)

    def test_loader_requests_options_for_one_load_only(self):
        path = str(MODELS / "n_link_chain.py")
        model, name, _ = load_model(path, {"n": "4"})
        self.assertEqual((model.nq, name), (4, "n_link_chain_4"))
        model, name, _ = load_model(path)
        self.assertNotEqual(name, "n_link_chain_4")
        self.assertEqual(dict(REQUESTED_OPTIONS.get()), {})

    def test_unknown_option_is_refused_and_leaves_no_request(self):
        with self.assertRaisesRegex(ModelError, "not an option of this model"):
            load_model(str(MODELS / "pendulum.py"), {"n": "4"})
        self.assertEqual(dict(REQUESTED_OPTIONS.get()), {})


if __name__ == "__main__":
    unittest.main()
