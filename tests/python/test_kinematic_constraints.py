# SPDX-License-Identifier: BSD-3-Clause
"""Kinematic constraints in model files (dsl/kinematic_constraints.py): what is refused, with
the constraint's line, and what generation does with the rest.

Refused: undeclared symbols, a holonomic constraint that does not depend on q, a velocity
constraint that is not linear in the speeds or does not involve them, as many constraints as
speeds, a redundant or an inconsistent set at the initial state, a rolling wheel in 2D or on
something that is no body, a loop between things that are no points, constraints in an atlas.
Accepted: initial values near the constraints are moved onto them and the report says so; a
rolling wheel adds a contact-height constraint only where the coordinates do not satisfy it;
a URDF robot takes a loop closure in its model file.
"""

from __future__ import annotations

import tempfile
import textwrap
import unittest
from pathlib import Path

from gencoord.errors import ModelError
from gencoord.generate.load import load_model
from gencoord.generate.stages import generate

from .support import MARK, MODELS, describe, marked_line, run_generate

CARTESIAN = """\
from gencoord import Model, sqrt
model = Model(dim=2)
x = model.coordinate("x", "bob, x (m)", initial=0.6)
y = model.coordinate("y", "bob, y (m)", initial=-0.8)
l = model.parameter("l", 1.0, "rod length (m)")
model.particle("bob", mass=1, position=[x, y])
model.gravity([0, -9.81])
"""


class ConstraintInputTest(unittest.TestCase):

    def setUp(self):
        self.scratch = tempfile.TemporaryDirectory(prefix="gencoord-constraints-")

    def tearDown(self):
        self.scratch.cleanup()

    def write(self, source: str, stem: str = "constrained") -> Path:
        path = Path(self.scratch.name) / f"{stem}.py"
        path.write_text(textwrap.dedent(source), encoding="utf-8")
        return path

    def refused(self, source: str, *fragments: str) -> None:
        """generate() refuses the model with every fragment, at the line marked MARK."""
        path = self.write(source)
        with self.assertRaises(ModelError) as caught:
            generate(str(path))
        message = str(caught.exception)
        self.assertIn(f"{path.name}:{marked_line(source)}:", message)
        for fragment in fragments:
            self.assertIn(fragment, message)

    def test_undeclared_symbols(self):
        self.refused(CARTESIAN + f"model.holonomic_constraint(x**2 + y**2 - k**2)  {MARK}\n"
                     .replace("k**2", "__import__('sympy').Symbol('k')**2"),
                     "holonomic constraint 'constraint_0'", "uses k, which is not declared")

    def test_a_holonomic_constraint_must_depend_on_q(self):
        self.refused(CARTESIAN + f"model.holonomic_constraint(l - 1, name='rod')  {MARK}\n",
                     "holonomic constraint 'rod'", "does not depend on the coordinates")

    def test_a_velocity_constraint_must_be_linear_in_the_speeds(self):
        self.refused(CARTESIAN + "xd, yd = model.rate(x), model.rate(y)\n"
                     f"model.velocity_constraint(xd**2 - yd, name='v')  {MARK}\n",
                     "velocity constraint 'v'", "not linear in the speeds")

    def test_a_velocity_constraint_must_involve_the_speeds(self):
        self.refused(CARTESIAN + "xd = model.rate(x)\n"
                     f"model.velocity_constraint(0 * xd + x, name='v')  {MARK}\n",
                     "velocity constraint 'v'", "does not involve the speeds")

    def test_as_many_constraints_as_speeds_leave_no_motion(self):
        self.refused(CARTESIAN + "model.holonomic_constraint(x**2 + y**2 - l**2, name='rod')\n"
                     f"model.holonomic_constraint(x - 0.6, name='wall')  {MARK}\n",
                     "2 constraints on 2 speeds leave no motion")

    def test_a_redundant_constraint_is_named(self):
        self.refused(CARTESIAN.replace('position=[x, y])', 'position=[x, y, z])')
                     .replace("dim=2", "dim=3")
                     .replace('model.gravity([0, -9.81])', 'model.gravity([0, -9.81, 0])')
                     .replace('l = model', 'z = model.coordinate("z", "bob, z (m)")\nl = model')
                     + "model.holonomic_constraint(x**2 + y**2 + z**2 - l**2, name='rod')\n"
                     f"model.holonomic_constraint(2 * (x**2 + y**2 + z**2 - l**2), name='again')"
                     f"  {MARK}\n",
                     "holonomic constraint 'again'", "redundant or inconsistent")

    def test_an_inconsistent_set_is_refused(self):
        self.refused(CARTESIAN.replace('position=[x, y])', 'position=[x, y, z])')
                     .replace("dim=2", "dim=3")
                     .replace('model.gravity([0, -9.81])', 'model.gravity([0, -9.81, 0])')
                     .replace('l = model', 'z = model.coordinate("z", "bob, z (m)")\nl = model')
                     + "model.holonomic_constraint(x**2 + y**2 + z**2 - l**2, name='rod')"
                     f"  {MARK}\nmodel.holonomic_constraint(x - 3 * l, name='far')\n",
                     "holonomic constraint 'rod'", "cannot be met near the initial coordinates "
                     "while the other holonomic constraints hold")

    def test_rolling_needs_a_body_in_3d(self):
        self.refused(CARTESIAN + f"model.rolling_wheel(None, 0.1)  {MARK}\n",
                     "rolling wheel", "3D model; this model is 2D")

    def test_a_loop_closes_between_points(self):
        self.refused(CARTESIAN + f"model.close_loop('bob', 'pivot', name='loop')  {MARK}\n",
                     "close_loop 'loop'", "not a point of the model")

    def test_the_command_line_error_is_one_line(self):
        source = CARTESIAN + f"model.holonomic_constraint(l - 1, name='rod')  {MARK}\n"
        path = self.write(source, "one_line")
        result = run_generate(path, "-o", self.scratch.name)
        self.assertEqual(result.returncode, 1, describe(result))
        self.assertNotIn("Traceback", result.stderr)
        self.assertEqual(len(result.stderr.strip().splitlines()), 1, describe(result))
        self.assertFalse((Path(self.scratch.name) / "one_line.hpp").exists())


class ConstraintGenerationTest(unittest.TestCase):

    def test_initial_values_are_moved_onto_the_constraints(self):
        generated = generate(str(MODELS / "four_bar.py"))
        notes = [line for line in generated.analysis if "moved onto" in line]
        self.assertEqual(len(notes), 1, generated.analysis)
        self.assertIn("crank 1.2 -> 1.19998", notes[0])
        self.assertIn("static constexpr int num_constraints = 2;", generated.header)
        self.assertIn('"loop_C_x", "loop_C_y"', generated.header)

    def test_a_rolling_wheel_adds_a_contact_height_only_where_needed(self):
        disk, _, _ = load_model(str(MODELS / "rolling_disk.py"))
        self.assertEqual([c.name for c in disk.velocity_constraints], ["rolling_x", "rolling_y"])
        self.assertEqual(disk.holonomic_constraints, [])  # the centre is r above the contact
        bicycle, _, _ = load_model(str(MODELS / "whipple_bicycle.py"))
        self.assertEqual([c.name for c in bicycle.holonomic_constraints],
                         ["front_rolling_contact"])  # sets the pitch
        self.assertEqual(len(bicycle.velocity_constraints), 4)
        self.assertEqual((bicycle.nq, bicycle.nv), (8, 8))

    def test_a_urdf_robot_takes_a_loop_closure_in_its_model_file(self):
        # the iiwa14 with its flange pinned where it starts: three holonomic constraints on a
        # 7-joint tree, which keeps its articulated-body recursion
        with tempfile.TemporaryDirectory(prefix="gencoord-pinned-") as scratch:
            path = Path(scratch) / "pinned_arm.py"
            path.write_text(PINNED_ARM.format(urdf=MODELS / "iiwa14.urdf"), encoding="utf-8")
            generated = generate(str(path))
        self.assertIn("static constexpr int num_constraints = 3;", generated.header)
        self.assertRegex(generated.header, r'"pinned_x",\s+"pinned_y",\s+"pinned_z"')
        self.assertFalse([line for line in generated.analysis if "moved onto" in line])
        self.assertIn("qddot: articulated-body recursion", "\n".join(generated.analysis))


PINNED_ARM = """\
from gencoord import Model, load_urdf
model = Model(dim=3)
links = load_urdf(model, "{urdf}")
for coordinate, angle in zip(model.coordinates, [0.3, 0.8, -0.2, -1.2, 0.4, 0.9, 0.1]):
    coordinate.initial = angle
body = links["iiwa_link_7"].body
flange = body.point([0, 0, 0.045], name="flange")
start = {{c.symbol: c.initial for c in model.coordinates}}
start.update({{p.symbol: p.default for p in model.parameters}})
flange_at_start = [float(x.subs(start)) for x in body.frame.point([0, 0, 0.045])]
anchor = model.fixed_point("anchor", flange_at_start)
model.close_loop(flange, anchor, name="pinned")
"""


if __name__ == "__main__":
    unittest.main()
