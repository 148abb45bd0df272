# SPDX-License-Identifier: BSD-3-Clause
"""URDF <mimic> joints (tree_models/mimic_gripper.urdf: a prismatic finger mirrored by another
at 1.5 times its travel plus 1 cm, and a thumb turning at -0.5 times the shoulder, both with
damping): the coupling is eliminated from the coordinates. With q_full = (shoulder, finger,
1.5 finger + 0.01, -0.5 shoulder) = f(q) and its constant Jacobian G, the mimic model's mass
matrix must be G^T Mt_full G and its forces G^T (Ft + Fi)_full at v_full = G v, where the full
model is the same file without <mimic>, derived on its own. Also: the refusals, each naming
its joint and line, and that such a tree leaves the articulated-body recursion for the dense
form."""

from __future__ import annotations

import random
import re
import tempfile
import unittest
from pathlib import Path

import sympy as sp

from gencoord import Model, ModelError, load_urdf
from gencoord.derive.body_tree import body_tree
from gencoord.derive.dense import derive

GRIPPER = Path(__file__).parent / "tree_models" / "mimic_gripper.urdf"


def loaded(text: str) -> Model:
    with tempfile.TemporaryDirectory(prefix="gencoord-mimic-") as folder:
        path = Path(folder) / "gripper.urdf"
        path.write_text(text, encoding="utf-8")
        model = Model(dim=3)
        load_urdf(model, str(path))
        return model


class MimicTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        text = GRIPPER.read_text(encoding="utf-8")
        cls.mimic = loaded(text)
        cls.full = loaded(re.sub(r"<mimic [^>]*/>", "", text))
        cls.derived = derive(cls.mimic)
        cls.full_derived = derive(cls.full)

    def test_a_mimic_joint_has_no_coordinate(self):
        self.assertEqual([c.name for c in self.mimic.coordinates], ["shoulder", "finger"])
        self.assertEqual(sorted(c.name for c in self.full.coordinates),
                         ["finger", "finger_mirror", "shoulder", "thumb_turn"])
        self.assertIsNone(body_tree(self.mimic))  # no articulated-body recursion
        self.assertIsNotNone(body_tree(self.full))

    def test_dynamics_are_the_full_models_on_the_coupling(self):
        shoulder, finger = (c.symbol for c in self.mimic.coordinates)
        full_of = {"shoulder": shoulder, "finger": finger,
                   "finger_mirror": 1.5 * finger + 0.01, "thumb_turn": -0.5 * shoulder}
        full_q = [c.symbol for c in self.full.coordinates]
        mapping = sp.Matrix([full_of[c.name] for c in self.full.coordinates])
        G = mapping.jacobian([shoulder, finger])
        v, full_v = self.derived.v, self.full_derived.v
        rng = random.Random(5)
        for _ in range(4):
            values = {shoulder: rng.uniform(-1.5, 1.5), finger: rng.uniform(0.0, 0.04),
                      **{s: rng.uniform(-2, 2) for s in v},
                      **{p.symbol: p.default for p in self.mimic.parameters}}
            on_coupling = dict(zip(full_q, [e.subs(values) for e in mapping]))
            on_coupling.update({p.symbol: p.default for p in self.full.parameters})
            on_coupling.update(zip(full_v, G.subs(values) * sp.Matrix([values[s] for s in v])))
            full_mass = self.full_derived.mass_matrix.subs(on_coupling)
            full_forces = (self.full_derived.applied_forces
                           + self.full_derived.inertial_forces).subs(on_coupling)
            mass = self.derived.mass_matrix.subs(values)
            forces = (self.derived.applied_forces + self.derived.inertial_forces).subs(values)
            for got, expected in ((mass, G.T * full_mass * G), (forces, G.T * full_forces)):
                error = max(abs(float(e)) for e in (got - expected))
                scale = max(abs(float(e)) for e in expected)
                self.assertLess(error, 1e-12 * scale)

    def test_refusals_name_the_joint_and_line(self):
        text = GRIPPER.read_text(encoding="utf-8")
        mimic = '<mimic joint="finger" multiplier="1.5" offset="0.01"/>'
        cases = [
            (text.replace(mimic, '<mimic joint="nowhere"/>'),
             r"joint 'finger_mirror': it follows joint 'nowhere', which is not a <joint>"),
            (text.replace(mimic, '<mimic joint="finger_mirror"/>'),
             r"joint 'finger_mirror': it follows itself"),
            (text.replace(mimic, '<mimic joint="thumb_turn"/>'),
             r"it follows joint 'thumb_turn', which follows 'shoulder'; follow that joint"),
            (text.replace(mimic, '<mimic/>'), r"<mimic> needs joint="),
            (text.replace(mimic, '<mimic joint="finger" multiplier="x"/>'), r"multiplier"),
            (text.replace('<mimic joint="shoulder" multiplier="-0.5"/>',
                          '<mimic joint="finger_mirror"/>').replace(mimic, ""),
             r"joint 'thumb_turn': it follows joint 'finger_mirror', which comes after it"),
        ]
        for broken, message in cases:
            with self.subTest(message=message):
                with self.assertRaisesRegex(ModelError, message) as raised:
                    loaded(broken)
                self.assertRegex(str(raised.exception), r"gripper\.urdf:\d+: error: ")


if __name__ == "__main__":
    unittest.main()
