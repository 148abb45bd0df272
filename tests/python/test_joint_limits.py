# SPDX-License-Identifier: BSD-3-Clause
"""Joint limits: what a model records from `model.limit(...)`, from a joint's `Limits` and from
a URDF `<limit>`, the header's members (each limit's coordinate, its speed, its ends and its
speed and effort ratings), and every refusal with its item. The runtime's enforcement is tested in
tests/robots/joint_limits_test.cc."""

from __future__ import annotations

import math
import tempfile
import textwrap
import unittest
from pathlib import Path

from gencoord import (Continuous, Free, Limits, Model, ModelError, Origin, Prismatic, Revolute,
                      add_link)
from gencoord.generate.stages import generate

INERTIA = [[0.02, 0, 0], [0, 0.03, 0], [0, 0, 0.04]]

URDF = """<robot name="limited">
  <link name="base"/>
  <link name="arm"><inertial><mass value="1"/><origin xyz="0 0 -0.5"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="wrist"><inertial><mass value="0.5"/><origin xyz="0 0 -0.1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.005" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="finger"><inertial><mass value="0.1"/>
    <inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 1 0"/><limit lower="-1.5" upper="2" effort="10" velocity="3"/></joint>
  <joint name="twist" type="continuous"><parent link="arm"/><child link="wrist"/>
    <origin xyz="0 0 -1"/><axis xyz="0 0 1"/><limit effort="5" velocity="3"/></joint>
  <joint name="slide" type="prismatic"><parent link="wrist"/><child link="finger"/>
    <origin xyz="0 0 -0.2"/><axis xyz="1 0 0"/><limit upper="0.04" effort="1" velocity="1"/>
  </joint>
</robot>
"""


class ModelLimitsTest(unittest.TestCase):

    def _pendulum(self) -> tuple[Model, object]:
        model = Model(dim=2)
        q = model.coordinate("theta")
        model.particle("bob", 1.0, [0, -1])
        return model, q

    def test_a_limit_records_its_ends_and_open_sides_are_infinite(self):
        model, q = self._pendulum()
        model.limit(q, lower=-0.5)
        (limit,) = model.limits
        self.assertEqual((limit.name, limit.lower, limit.upper, limit.velocity, limit.effort),
                         ("theta", -0.5, math.inf, math.inf, math.inf))

    def test_a_joint_with_limits_declares_them_and_a_continuous_joint_no_range(self):
        model = Model(dim=3)
        arm = add_link(model, "arm", None, Revolute([0, 1, 0], Origin(), Limits(-1, 2),
                                                    name="shoulder"), mass=1.0, inertia=INERTIA)
        hand = add_link(model, "hand", arm, Continuous([0, 0, 1], Origin(), Limits(-1, 1)),
                        mass=1.0, inertia=INERTIA)
        add_link(model, "wrist", hand, Continuous([1, 0, 0], Origin(), Limits(velocity=4)),
                 mass=1.0, inertia=INERTIA)
        add_link(model, "finger", arm, Prismatic([1, 0, 0], Origin(), Limits(effort=3)),
                 mass=0.1, inertia=INERTIA)
        # a joint with only an effort rating is a limit without a range: its effort is rated
        self.assertEqual([(limit.name, limit.lower, limit.upper, limit.velocity, limit.effort)
                          for limit in model.limits],
                         [("shoulder", -1.0, 2.0, math.inf, math.inf),
                          ("wrist_joint", -math.inf, math.inf, 4.0, math.inf),
                          ("finger_joint", -math.inf, math.inf, math.inf, 3.0)])

    def test_refusals_name_the_limit(self):
        model, q = self._pendulum()
        free = Model(dim=3)
        add_link(free, "body", None, Free(Origin()), mass=1.0, inertia=INERTIA)
        quaternion = free.coordinates[3].symbol
        cases = [
            (lambda: model.limit(q), "give a lower end, an upper end, a velocity or effort "
                                     "rating"),
            (lambda: model.limit(q, 1, 0), "its lower end 1 exceeds its upper end 0"),
            (lambda: model.limit(q, math.nan, 1), "its lower end must be finite"),
            (lambda: model.limit(q, -math.inf), "leave it out"),
            (lambda: model.limit(q, "low"), "its lower end must be a number, not 'low'"),
            (lambda: model.limit(q, velocity=0), "its velocity rating must be positive"),
            (lambda: model.limit(q, effort=-2), "its effort rating must be positive, not -2"),
            (lambda: model.limit(q, effort=math.inf), "its effort rating must be finite"),
            (lambda: free.limit(quaternion, -1, 1), "body_qw belongs to a free or ball joint"),
            (lambda: model.limit(model.t, 0, 1), "t is not a declared coordinate"),
        ]
        for make, message in cases:
            with self.subTest(message=message):
                with self.assertRaisesRegex(ModelError, message):
                    make()
        model.limit(q, 0, 1)
        with self.assertRaisesRegex(ModelError, "theta is limited twice"):
            model.limit(q, 0, 2)


class HeaderLimitsTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        folder = tempfile.TemporaryDirectory()
        cls.addClassCleanup(folder.cleanup)
        urdf = Path(folder.name) / "limited.urdf"
        urdf.write_text(URDF)
        cls.urdf_header = generate(str(urdf)).header
        floating = Path(folder.name) / "floating_limited.py"
        floating.write_text(textwrap.dedent("""\
            from gencoord import Free, Limits, Model, Origin, Revolute, add_link
            INERTIA = [[0.02, 0, 0], [0, 0.03, 0], [0, 0, 0.04]]
            model = Model(dim=3)
            body = add_link(model, "body", None, Free(Origin()), mass=1.0, inertia=INERTIA)
            add_link(model, "arm", body, Revolute([0, 1, 0], Origin(xyz=[0, 0, -0.2]),
                                                  Limits(-0.5, 0.5)), mass=1.0, inertia=INERTIA)
        """))
        cls.floating_header = generate(str(floating)).header

    def test_a_urdf_limit_is_in_the_header_and_an_open_end_defaults_as_urdf_says(self):
        # URDF: a missing lower end of a prismatic joint's <limit> is 0; the continuous joint
        # has no range, only its velocity rating
        infinity = "std::numeric_limits<double>::infinity()"
        for text in ("static constexpr int num_limits = 3;",
                     'limit_names{{"shoulder", "twist", "slide"}}',
                     "limited_coordinates{{0, 1, 2}}", "limited_speeds{{0, 1, 2}}",
                     f"lower_limits{{{{-1.5, -{infinity}, 0.0}}}}",
                     f"upper_limits{{{{2.0, {infinity}, 0.04}}}}",
                     "velocity_limits{{3.0, 3.0, 1.0}}", "effort_limits{{10.0, 5.0, 1.0}}"):
            self.assertIn(text, " ".join(self.urdf_header.split()))

    def test_a_limit_after_a_free_joint_names_its_speed_apart_from_its_coordinate(self):
        # q: position (3), quaternion (4), the arm angle; v: twist (6), the arm rate
        for text in ("limited_coordinates{{7}}", "limited_speeds{{6}}",
                     "lower_limits{{-0.5}}", "upper_limits{{0.5}}"):
            self.assertIn(text, self.floating_header)

    def test_an_open_side_is_infinite_in_cxx(self):
        folder = tempfile.TemporaryDirectory()
        self.addCleanup(folder.cleanup)
        path = Path(folder.name) / "half_limited.py"
        path.write_text(textwrap.dedent("""\
            import sympy as sp
            from gencoord import Model
            model = Model(dim=2)
            theta = model.coordinate("theta")
            model.particle("bob", 1.0, [sp.sin(theta), -sp.cos(theta)])
            model.limit(theta, upper=0.25)
        """))
        header = generate(str(path)).header
        self.assertIn("lower_limits{{-std::numeric_limits<double>::infinity()}}", header)
        self.assertIn("upper_limits{{0.25}}", header)


if __name__ == "__main__":
    unittest.main()
