# SPDX-License-Identifier: BSD-3-Clause
"""URDF import: every refusal names the file, the line and the element without a traceback;
a valid file's link frames match forward kinematics computed by hand; rpy and axis follow
URDF's conventions; ./generate accepts a .urdf file."""

from __future__ import annotations

import contextlib
import io
import math
import random
import tempfile
import textwrap
import unittest
from pathlib import Path

import sympy as sp

from gencoord import Model, load_urdf
from gencoord.checks.atlas import check_atlas
from gencoord.generate.cli import main as generate_main
from gencoord.errors import ModelError
from gencoord.urdf.description import read_urdf
from gencoord.urdf.load import urdf_model

from .support import MODELS, describe, run_generate

HERE = "<!-- here -->"  # marks the line an error must name


def link(name: str, mass: float = 1.0, mark: str = "") -> str:
    return f"""<link name="{name}">{mark}
  <inertial>
    <mass value="{mass}"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.1"/>
  </inertial>
</link>"""


def joint(name: str, parent: str, child: str, kind: str = "revolute", mark: str = "",
          extra: str = "") -> str:
    return f"""<joint name="{name}" type="{kind}">{mark}
  <parent link="{parent}"/>
  <child link="{child}"/>
  <axis xyz="0 0 1"/>{extra}
</joint>"""


def robot(*parts: str) -> str:
    return '<?xml version="1.0"?>\n<robot name="test">\n' + "\n".join(parts) + "\n</robot>\n"


# A valid two-link arm whose forward kinematics the tests compute by hand.
TWO_LINKS = robot(
    '<link name="base"/>',
    """<link name="upper">
  <inertial>
    <origin xyz="0 0 0.2" rpy="0 0 0"/>
    <mass value="2"/>
    <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.05"/>
  </inertial>
  <visual><geometry><box size="0.1 0.1 0.4"/></geometry></visual>
  <collision><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.05" length="0.4"/></geometry>
  </collision>
</link>""",
    """<link name="lower">
  <inertial>
    <origin xyz="0.01 0 0.15" rpy="0.1 0.2 0.3"/>
    <mass value="1"/>
    <inertia ixx="0.05" ixy="0.001" ixz="-0.002" iyy="0.05" iyz="0.003" izz="0.02"/>
  </inertial>
</link>""",
    """<joint name="shoulder" type="revolute">
  <parent link="base"/><child link="upper"/>
  <origin xyz="0 0 0.1" rpy="0 0 1.5707963267948966"/>
  <axis xyz="0 1 0"/>
  <limit lower="-2" upper="2" effort="10" velocity="3"/>
  <dynamics damping="0.5"/>
</joint>""",
    """<joint name="elbow" type="revolute">
  <parent link="upper"/><child link="lower"/>
  <origin xyz="0.05 0 0.4" rpy="0.3 -0.2 0.7"/>
  <axis xyz="1 1 0"/>
  <limit lower="0.5" upper="2"/>
</joint>""")


# Hand-written rotations and products (plain floats), independent of gencoord/dsl/frames.py.
def rx(a):
    return [[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]]


def ry(a):
    return [[math.cos(a), 0, math.sin(a)], [0, 1, 0], [-math.sin(a), 0, math.cos(a)]]


def rz(a):
    return [[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def apply(a, v):
    return [sum(a[i][k] * v[k] for k in range(3)) for i in range(3)]


def rodrigues(axis, angle):
    n = math.sqrt(sum(c * c for c in axis))
    x, y, z = (c / n for c in axis)
    c, s, C = math.cos(angle), math.sin(angle), 1 - math.cos(angle)
    return [[c + x * x * C, x * y * C - z * s, x * z * C + y * s],
            [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
            [z * x * C - y * s, z * y * C + x * s, c + z * z * C]]


def pose(rotation, origin, child_rotation, child_origin):
    """parent * child for (R, p) pairs."""
    return (matmul(rotation, child_rotation),
            [o + d for o, d in zip(origin, apply(rotation, child_origin))])


def numeric(matrix: sp.Matrix, values: dict) -> list[float]:
    return [float(entry) for entry in matrix.xreplace(values)]


class UrdfRefusalTest(unittest.TestCase):
    """Each bad file fails ./generate with one line: file:line: error: item: message."""

    def setUp(self):
        self.scratch = tempfile.TemporaryDirectory(prefix="gencoord-urdf-")
        self.folder = Path(self.scratch.name)

    def tearDown(self):
        self.scratch.cleanup()

    def refuse(self, text: str, *fragments: str, stem: str = "bad"):
        path = self.folder / f"{stem}.urdf"
        path.write_text(text, encoding="utf-8")
        line = next(n for n, t in enumerate(text.splitlines(), start=1) if HERE in t)
        errors = io.StringIO()
        with contextlib.redirect_stderr(errors), contextlib.redirect_stdout(io.StringIO()):
            status = generate_main([str(path), "-o", str(self.folder / "out")])
        message = errors.getvalue()
        self.assertEqual(status, 1, message)
        self.assertNotIn("Traceback", message)
        self.assertNotIn("internal error", message)
        self.assertEqual(len(message.strip().splitlines()), 1, message)
        self.assertTrue(message.startswith(f"{path}:{line}: error: "), message)
        for fragment in fragments:
            self.assertIn(fragment, message)
        self.assertFalse((self.folder / "out").exists(), "a refused file wrote output")
        return message

    def test_malformed_xml(self):
        self.refuse(robot(link("a"), '<link name="b">', "</robots>" + HERE),
                    "malformed XML", "mismatched tag")

    def test_unknown_joint_type(self):
        self.refuse(robot(link("a"), link("b"), joint("ball", "a", "b", "ball", HERE)),
                    "joint 'ball'", "'ball' is not a joint type")

    def test_planar_joint(self):
        self.refuse(robot(link("a"), link("b"), joint("slide", "a", "b", "planar", HERE)),
                    "joint 'slide'", "planar joints are not supported")

    def test_missing_parent_link(self):
        self.refuse(robot(link("a"), link("b"), joint("j", "nowhere", "b", mark=HERE)),
                    "joint 'j'", "parent link 'nowhere' is not a <link>")

    def test_missing_child_link(self):
        self.refuse(robot(link("a"), joint("j", "a", "ghost", mark=HERE)),
                    "joint 'j'", "child link 'ghost' is not a <link>")

    def test_link_with_two_parents(self):
        self.refuse(robot(link("a"), link("b"), link("c"), joint("j1", "a", "c"),
                          joint("j2", "b", "c", mark=HERE)),
                    "joint 'j2'", "link 'c' has two parents", "joint 'j1'")

    def test_cycle(self):
        self.refuse(robot(link("root"), link("a"), link("b"), link("c"), joint("j1", "root", "a"),
                          joint("j2", "b", "c"), joint("j3", "c", "b", mark=HERE)),
                    "joint 'j3'", "cycle through links b, c")

    def test_cycle_without_root(self):
        self.refuse(robot(link("a"), link("b"), joint("j1", "a", "b"),
                          joint("j2", "b", "a", mark=HERE)),
                    "joint 'j2'", "cycle through links a, b")

    def test_several_roots(self):
        self.refuse(robot(link("a"), link("b"), link("c", mark=HERE), joint("j", "a", "b")),
                    "link 'c'", "2 roots (a, c)")

    def test_non_positive_mass(self):
        text = robot(link("a"), link("b", mass=0.0), joint("j", "a", "b"))
        self.refuse(text.replace('<mass value="0.0"/>', '<mass value="0.0"/>' + HERE),
                    "link 'b'", "the mass is 0; give a positive mass")

    def test_inertia_not_positive_definite(self):
        text = robot(link("a"), link("b"), joint("j", "a", "b")).replace(
            '<inertia ixx="0.1" iyy="0.1" izz="0.1"/>\n  </inertial>\n</link>\n<joint',
            '<inertia ixx="0.1" ixy="0.2" iyy="0.1" izz="0.1"/>' + HERE
            + '\n  </inertial>\n</link>\n<joint')
        self.refuse(text, "link 'b'", "not positive definite", "principal moments")

    def test_inertia_breaks_triangle_inequality(self):
        text = robot(link("a"), link("b"), joint("j", "a", "b")).replace(
            '<inertia ixx="0.1" iyy="0.1" izz="0.1"/>\n  </inertial>\n</link>\n<joint',
            '<inertia ixx="0.1" iyy="0.1" izz="0.2"/>' + HERE + '\n  </inertial>\n</link>\n<joint')
        self.refuse(text, "link 'b'", "triangle inequality")

    def test_zero_axis(self):
        text = robot(link("a"), link("b"), joint("j", "a", "b"))
        self.refuse(text.replace('<axis xyz="0 0 1"/>', '<axis xyz="0 0 0"/>' + HERE),
                    "joint 'j'", "the axis is zero")

    def test_non_numeric_values(self):
        text = robot(link("a"), link("b", mass="heavy", mark=""), joint("j", "a", "b"))
        self.refuse(text.replace('<mass value="heavy"/>', '<mass value="heavy"/>' + HERE),
                    "link 'b'", '<mass value="heavy"> is not a list of numbers')
        text = robot(link("a"), link("b"), joint("j", "a", "b", extra=(
            '\n  <origin xyz="0 0 ${l}"/>' + HERE)))
        self.refuse(text, "joint 'j'", "is not a list of numbers")
        text = robot(link("a"), link("b"), joint("j", "a", "b", extra=(
            '\n  <origin xyz="0 0"/>' + HERE)))
        self.refuse(text, "joint 'j'", "has 2 numbers; give 3")
        text = robot(link("a"), link("b"), joint("j", "a", "b", extra=(
            '\n  <limit lower="nan" upper="1"/>' + HERE)))
        self.refuse(text, "joint 'j'", "not finite")

    def test_no_link_with_a_mass(self):
        self.refuse(robot(f'<link name="a"/>{HERE}', '<link name="b"/>', joint("j", "a", "b")),
                    "no link of the robot has a mass", "<inertial>")

    def test_a_robot_without_a_moving_joint(self):
        self.refuse(robot(link("a", mark=HERE), link("b"), joint("j", "a", "b", kind="fixed")),
                    "no joint of the robot moves (it has 1 joints")

    def test_entity_expansion_and_external_entities(self):
        levels = "".join(f'<!ENTITY e{k} "{f"&e{k - 1};" * 10}">' for k in range(1, 9))
        head = '<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY e0 "aaaaaaaaaa">'
        self.refuse(head + levels + f']>\n<robot name="r">{HERE}<link name="&e8;"/></robot>\n',
                    "malformed XML", "amplification")  # 10^9 characters, refused by expat
        head = '<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY x SYSTEM "file:///etc/passwd">'
        self.refuse(head + f']>\n<robot name="r">{HERE}<link name="&x;"/></robot>\n',
                    "malformed XML", "external entity")

    def test_a_long_comment_is_read_in_one_piece(self):
        """A valid URDF behind a 5 MB comment loads (fed to expat in blocks, the comment was
        rescanned at every block: minutes for a few megabytes)."""
        text = robot(link("a"), link("b"), joint("j", "a", "b"))
        path = self.folder / "commented.urdf"
        declaration, _, rest = text.partition("\n")
        path.write_text(f"{declaration}\n<!-- {'x' * 5_000_000} -->\n{rest}", encoding="utf-8")
        model = urdf_model(str(path))
        self.assertEqual([link.name for link in model.links], ["a", "b"])

    def test_reversed_limits(self):
        text = robot(link("a"), link("b"), joint("j", "a", "b", extra=(
            '\n  <limit lower="2" upper="1" effort="1" velocity="1"/>' + HERE)))
        self.refuse(text, "joint 'j'", '<limit lower="2" upper="1"> is reversed')

    def test_duplicate_names(self):
        self.refuse(robot(link("a"), link("a", mark=HERE)), "link 'a'", "a second link")
        self.refuse(robot(link("a"), link("b"), link("c"), joint("j", "a", "b"),
                          joint("j", "a", "c", mark=HERE)), "joint 'j'", "a second joint")

    def test_mimic_of_a_joint_not_in_the_file(self):
        self.refuse(robot(link("a"), link("b"), joint("j", "a", "b", extra=(
            '\n  <mimic joint="k" multiplier="2"/>' + HERE))), "joint 'j'",
            "it follows joint 'k', which is not a <joint> of this file")

    def test_joint_without_child(self):
        self.refuse(robot(link("a"), '<joint name="j" type="fixed">' + HERE
                          + '<parent link="a"/></joint>'),
                    "joint 'j'", '<child link="...">')

    def test_floating_joint_away_from_the_root(self):
        self.refuse(robot(link("a"), link("b"), link("c"), joint("j", "a", "b"),
                          joint("free", "b", "c", "floating", HERE)),
                    "joint 'free'", "floating joint joins the root link")

    def test_not_a_urdf(self):
        self.refuse('<?xml version="1.0"?>\n<sdf version="1.6">' + HERE + '\n</sdf>\n',
                    "the root element is <sdf>")
        self.refuse(robot(link("a"), '<xacro:property name="l" value="1"/>' + HERE),
                    "xacro file")

    def test_load_urdf_error_names_the_urdf(self):
        """From a model file too, a URDF's problem is reported at the URDF's line."""
        path = self.folder / "arm.urdf"
        text = robot(link("a"), link("b"), joint("j", "a", "b", "ball", HERE))
        path.write_text(text, encoding="utf-8")
        with self.assertRaises(ModelError) as caught:
            load_urdf(Model(dim=3), str(path))
        line = next(n for n, t in enumerate(text.splitlines(), start=1) if HERE in t)
        self.assertEqual((caught.exception.filename, caught.exception.line), (str(path), line))
        self.assertEqual(caught.exception.item, "joint 'j'")

    def test_generate_reports_in_one_line(self):
        """The real command: one line on stderr, exit status 1."""
        path = self.folder / "broken.urdf"
        path.write_text(robot(link("a"), "<link"), encoding="utf-8")
        result = run_generate(str(path), "-o", str(self.folder / "out"))
        self.assertEqual(result.returncode, 1, describe(result))
        self.assertRegex(result.stderr, rf"^{path}:\d+: error: malformed XML", describe(result))
        self.assertNotIn("Traceback", result.stderr, describe(result))


class UrdfReadTest(unittest.TestCase):

    def setUp(self):
        self.scratch = tempfile.TemporaryDirectory(prefix="gencoord-urdf-")
        self.path = Path(self.scratch.name) / "two.urdf"
        self.path.write_text(TWO_LINKS, encoding="utf-8")

    def tearDown(self):
        self.scratch.cleanup()

    def test_description(self):
        robot = read_urdf(str(self.path))
        self.assertEqual(robot.root, "base")
        self.assertEqual(robot.order(), ["base", "upper", "lower"])
        upper = robot.links["upper"]
        self.assertEqual([(g.kind, g.shape) for g in upper.geometry],
                         [("visual", "box"), ("collision", "cylinder")])
        self.assertEqual(upper.geometry[1].attributes, {"radius": "0.05", "length": "0.4"})
        self.assertEqual(upper.inertial.mass, 2.0)
        shoulder = robot.joints["upper"].joint
        self.assertEqual((shoulder.limits.lower, shoulder.limits.upper, shoulder.limits.effort,
                          shoulder.limits.velocity), (-2.0, 2.0, 10.0, 3.0))
        self.assertEqual(shoulder.damping, 0.5)
        # rpy within double precision of pi/2 is exact
        self.assertEqual(shoulder.origin.rpy[2], sp.pi / 2)
        self.assertIsNone(robot.links["base"].inertial)

    def test_link_frames_match_forward_kinematics(self):
        model = Model(dim=3)
        links = load_urdf(model, str(self.path))
        q1, q2 = links.coordinates["shoulder"], links.coordinates["elbow"]
        self.assertEqual([c.name for c in model.coordinates], ["shoulder", "elbow"])
        rng = random.Random(7)
        for _ in range(4):
            a, b = rng.uniform(-3, 3), rng.uniform(-3, 3)
            values = {q1: a, q2: b}
            # shoulder: at (0, 0, 0.1), turned by yaw pi/2, rotating about its y axis
            R1, p1 = pose(rz(math.pi / 2), [0, 0, 0.1], ry(a), [0, 0, 0])
            # elbow: at (0.05, 0, 0.4) in upper, rpy = Rz Ry Rx, about (1, 1, 0)/sqrt(2)
            R2, p2 = pose(*pose(R1, p1, matmul(rz(0.7), matmul(ry(-0.2), rx(0.3))),
                                [0.05, 0, 0.4]), rodrigues([1, 1, 0], b), [0, 0, 0])
            for frame, (R, p) in ((links["upper"].frame, (R1, p1)),
                                  (links["lower"].frame, (R2, p2))):
                for got, want in zip(numeric(frame.rotation, values), sum(R, [])):
                    self.assertAlmostEqual(got, want, places=12)
                for got, want in zip(numeric(frame.origin, values), p):
                    self.assertAlmostEqual(got, want, places=12)
            # the lower body's centre of mass: at (0.01, 0, 0.15) in the lower link
            com = numeric(links["lower"].body.frame.origin, values)
            for got, want in zip(com, [o + d for o, d in zip(p2, apply(R2, [0.01, 0, 0.15]))]):
                self.assertAlmostEqual(got, want, places=12)
            inertial = matmul(R2, matmul(rz(0.3), matmul(ry(0.2), rx(0.1))))
            for got, want in zip(numeric(links["lower"].body.frame.rotation, values),
                                 sum(inertial, [])):
                self.assertAlmostEqual(got, want, places=12)
        self.assertIsNone(links["base"].body)
        self.assertEqual(links["upper"].limits.upper, 2.0)
        self.assertIn("limits [-2, 2]", model.coordinates[0].description)
        # the elbow's range excludes 0: it starts at its lower limit
        self.assertEqual(model.coordinates[1].initial, 0.5)
        damping = [f for f in model.generalized_forces if f.coordinate.name == "shoulder"]
        self.assertEqual([f.force for f in damping], [-0.5 * model.rate(q1)])
        self.assertEqual(len(model.gravities), 1)
        self.assertEqual([p.name for p in model.parameters], ["g"])

    def test_rpy_and_axis_conventions(self):
        """rpy = (roll, pitch, yaw) is Rz(yaw) Ry(pitch) Rx(roll) about fixed axes; the axis is
        in the joint frame, so origin rpy (pi/2, 0, 0) turns axis z into -y."""
        path = Path(self.scratch.name) / "axes.urdf"
        path.write_text(robot('<link name="a"/>', '<link name="b"/>', '<link name="c"/>',
                              """<joint name="fixed_turn" type="fixed">
  <parent link="a"/><child link="b"/>
  <origin xyz="1 2 3" rpy="0.1 0.2 0.3"/>
</joint>""", """<joint name="hinge" type="continuous">
  <parent link="a"/><child link="c"/>
  <origin rpy="1.5707963267948966 0 0"/>
  <axis xyz="0 0 1"/>
</joint>"""), encoding="utf-8")
        model = Model(dim=3)
        links = load_urdf(model, str(path), gravity=False)
        want = matmul(rz(0.3), matmul(ry(0.2), rx(0.1)))
        for got, value in zip(numeric(links["b"].frame.rotation, {}), sum(want, [])):
            self.assertAlmostEqual(got, value, places=14)
        self.assertEqual(list(links["b"].frame.origin), [1, 2, 3])
        q = links.coordinates["hinge"]
        for angle in (0.4, -1.3):
            turned = matmul(rx(math.pi / 2), rz(angle))
            about_minus_y = rodrigues([0, -1, 0], angle)
            for got, value, other in zip(numeric(links["c"].frame.rotation, {q: angle}),
                                         sum(turned, []), sum(matmul(about_minus_y,
                                                                     rx(math.pi / 2)), [])):
                self.assertAlmostEqual(got, value, places=14)
                self.assertAlmostEqual(got, other, places=14)
        self.assertEqual(model.gravities, [])


PENDULUM = robot('<link name="world"/>', """<link name="rod">
  <inertial>
    <origin xyz="0 0 -0.5"/>
    <mass value="1.5"/>
    <inertia ixx="0.125" iyy="0.125" izz="0.002"/>
  </inertial>
</link>""", """<joint name="swing" type="continuous">
  <parent link="world"/><child link="rod"/>
  <axis xyz="0 1 0"/>
</joint>""")

FLOATING = robot('<link name="world"/>', link("box"), link("arm"),
                 joint("free", "world", "box", "floating"),
                 joint("hinge", "box", "arm", extra='\n  <dynamics damping="0.2"/>'))


# A massless base link on the floating joint, the mass on a trunk welded to it (Unitree's files)
MASSLESS_BASE = robot('<link name="world"/>', '<link name="base"/>', link("trunk"), link("arm"),
                      joint("free", "world", "base", "floating"),
                      joint("weld", "base", "trunk", "fixed"), joint("hinge", "trunk", "arm"))


class UrdfGenerateTest(unittest.TestCase):
    """./generate robot.urdf: the model takes the file's stem; a floating base is a free joint."""

    def setUp(self):
        self.scratch = tempfile.TemporaryDirectory(prefix="gencoord-urdf-")
        self.folder = Path(self.scratch.name)

    def tearDown(self):
        self.scratch.cleanup()

    def test_generate_writes_a_header(self):
        path = self.folder / "urdf_pendulum.urdf"
        path.write_text(PENDULUM, encoding="utf-8")
        result = run_generate(str(path), "-o", str(self.folder / "out"))
        self.assertEqual(result.returncode, 0, describe(result))
        header = (self.folder / "out" / "urdf_pendulum.hpp").read_text(encoding="utf-8")
        self.assertRegex(header, r"\bstruct UrdfPendulum\b")
        self.assertRegex(header, r"\bnq = 1;")
        self.assertIn("Robot 'test' from urdf_pendulum.urdf", header)

    def test_floating_base_is_a_free_joint(self):
        from gencoord.generate.load import load_model
        path = self.folder / "floater.urdf"
        path.write_text(FLOATING.replace('type="floating">', 'type="floating">\n  <origin '
                                         'xyz="0 0 2" rpy="0 0 1.5707963267948966"/>'),
                        encoding="utf-8")
        model, name, _ = load_model(str(path))
        self.assertEqual((name, model.chart, model.charts), ("floater", None, []))
        self.assertEqual([c.name for c in model.coordinates],
                         ["box_x", "box_y", "box_z", "box_qw", "box_qx", "box_qy", "box_qz",
                          "hinge"])
        self.assertEqual([s.name for s in model.speeds],
                         ["box_vx", "box_vy", "box_vz", "box_wx", "box_wy", "box_wz", "hinge"])
        # the floating joint's origin is the initial pose: z = 2, a quarter turn about z
        initial = [c.initial for c in model.coordinates]
        self.assertEqual(initial[:3], [0.0, 0.0, 2.0])
        for value, expected in zip(initial[3:7], [math.sqrt(0.5), 0, 0, math.sqrt(0.5)]):
            self.assertAlmostEqual(value, expected, places=15)
        self.assertEqual(len(model.generalized_forces), 1)  # the hinge's damping acts on q

    def test_a_massless_base_welded_to_its_trunk_floats(self):
        path = self.folder / "massless_base.urdf"
        path.write_text(MASSLESS_BASE, encoding="utf-8")
        result = run_generate(str(path), "-o", str(self.folder / "out"))
        self.assertEqual(result.returncode, 0, describe(result))
        header = (self.folder / "out" / "massless_base.hpp").read_text(encoding="utf-8")
        self.assertRegex(header, r"\bnq = 8;")
        self.assertRegex(header, r"\bnv = 7;")
        # alone, a massless base moves nothing: the rank check refuses it
        path.write_text(robot('<link name="world"/>', '<link name="base"/>', link("arm"),
                              joint("free", "world", "base", "floating"),
                              joint("hinge", "base", "arm")), encoding="utf-8")
        result = run_generate(str(path), "-o", str(self.folder / "out"))
        self.assertEqual(result.returncode, 1, describe(result))
        self.assertRegex(result.stderr, r"massless_base\.urdf.*error: .*redundant")

    def test_what_is_not_read_is_listed_once(self):
        from gencoord.generate.load import load_model
        path = self.folder / "shipped.urdf"
        path.write_text(robot(link("base"), link("arm"),
                              joint("hinge", "base", "arm",
                                    extra='\n  <dynamics damping="0.1" friction="0.3"/>'),
                              '<transmission name="t"/>', '<gazebo/>', '<gazebo/>'),
                        encoding="utf-8")
        model, _, _ = load_model(str(path))
        self.assertEqual(model.ignored, [  # the hinge's friction is read (test_joint_friction)
            "1 <transmission> element(s): actuator transmissions",
            "2 <gazebo> element(s): Gazebo extensions"])

    def test_a_point_mass_on_a_fixed_joint_joins_its_parent(self):
        point = ('<link name="imu"><inertial><origin xyz="0 0 0.5"/><mass value="2"/>'
                 '<inertia ixx="0" iyy="0" izz="0"/></inertial></link>')
        weld = ('<joint name="imu_weld" type="fixed"><origin xyz="0.5 0 0"/>'
                '<parent link="arm"/><child link="imu"/></joint>')
        path = self.folder / "point_mass.urdf"
        path.write_text(robot(link("base"), link("arm"), point, joint("hinge", "base", "arm"),
                              weld), encoding="utf-8")
        robot_description = read_urdf(str(path))
        self.assertIsNone(robot_description.links["imu"].inertial)
        arm = robot_description.links["arm"].inertial
        # 1 kg at the arm's origin and 2 kg at (0.5, 0, 0.5): the centre at a third of the way
        self.assertAlmostEqual(float(arm.mass), 3.0)
        for value, expected in zip(arm.origin.xyz, [1 / 3, 0, 1 / 3]):
            self.assertAlmostEqual(float(value), expected, places=15)
        # about the new centre: 0.1 + 1 kg and 2 kg at their offsets (parallel axes)
        offset_arm, offset_point = [-1 / 3, 0, -1 / 3], [1 / 6, 0, 1 / 6]
        expected_iyy = 0.1 + 1 * (offset_arm[0] ** 2 + offset_arm[2] ** 2) + \
            2 * (offset_point[0] ** 2 + offset_point[2] ** 2)
        self.assertAlmostEqual(float(arm.inertia[1, 1]), expected_iyy, places=14)
        path.write_text(robot(link("base"), point, joint("hinge", "base", "imu")),
                        encoding="utf-8")
        with self.assertRaisesRegex(ModelError, "link 'imu': a point mass .* on a moving joint"):
            read_urdf(str(path))

    def test_a_model_file_keeps_the_atlas_of_euler_charts(self):
        from gencoord.generate.load import load_model
        (self.folder / "floater.urdf").write_text(FLOATING, encoding="utf-8")
        (self.folder / "floater_atlas.py").write_text(
            "from gencoord import Model, load_urdf\n"
            "models = [Model(dim=3, chart=chart) for chart in ('zyx', 'yzx')]\n"
            "for model in models:\n"
            "    load_urdf(model, 'floater.urdf')\n"
            "model = models[0]\n"
            "model.add_chart(models[1])\n", encoding="utf-8")
        model, _, _ = load_model(str(self.folder / "floater_atlas.py"))
        self.assertEqual([model.chart, *(c.chart for c in model.charts)], ["zyx", "yzx"])
        for chart, angle in ((model, "yaw"), (model.charts[0], "heading")):
            self.assertEqual([c.name for c in chart.coordinates][::3], ["x", angle, "hinge"])
            # an atlas refuses forces on q: the damping is a torque pair between the bodies
            self.assertEqual(chart.generalized_forces, [])
            self.assertEqual(len(chart.torques), 2)
        check_atlas(model)

    def test_items_point_at_the_urdf_lines(self):
        from gencoord.generate.load import load_model
        path = self.folder / "floater.urdf"
        path.write_text(FLOATING, encoding="utf-8")
        model, _, _ = load_model(str(path))
        lines = FLOATING.splitlines()
        hinge = next(n for n, t in enumerate(lines, start=1) if 'name="hinge"' in t)
        free = next(n for n, t in enumerate(lines, start=1) if 'name="free"' in t)
        self.assertEqual(model.coordinates[-1].line, hinge)
        self.assertEqual({c.line for c in model.coordinates[:7]}, {free})
        self.assertEqual({g.line for g in model.generalized_forces}, {hinge})


class BuiltInRobotsTest(unittest.TestCase):
    """The robot descriptions in models/ load: joints, bodies, pins; numbers stay literals."""

    def load(self, stem: str):
        from gencoord.generate.load import load_model
        return load_model(str(MODELS / f"{stem}.urdf"))[0]

    def test_iiwa14(self):
        model = self.load("iiwa14")
        self.assertEqual([c.name for c in model.coordinates],
                         [f"iiwa_joint_{k}" for k in range(1, 8)])
        self.assertEqual([b.name for b in model.bodies], [f"iiwa_link_{k}" for k in range(1, 8)])
        self.assertEqual(len([c for c in model.constraints if type(c).__name__ == "Pin"]), 14)
        self.assertEqual([p.name for p in model.parameters], ["g"])
        self.assertEqual(len(model.generalized_forces), 7)  # damping 0.5 on every joint

    def test_quadruped(self):
        model = self.load("quadruped")
        self.assertEqual(len(model.coordinates), 12)
        # hip, thigh, calf and foot of each leg; the trunk is welded to the world
        self.assertEqual(len(model.bodies), 16)
        self.assertNotIn("trunk", [b.name for b in model.bodies])
        thigh = next(b for b in model.bodies if b.name == "FR_thigh")
        self.assertNotEqual(thigh.inertia[0, 2], 0)
        self.assertEqual([p.name for p in model.parameters], ["joint_friction_speed", "g"])
        # damping 0.01 and friction 0.2 on every joint
        self.assertEqual(sorted({f.name.rsplit("_", 1)[1] for f in model.generalized_forces}),
                         ["damping", "friction"])
        self.assertEqual(len(model.generalized_forces), 24)


class UrdfModelFileTest(unittest.TestCase):
    """load_urdf from a model file, relative to it, with forces added on top."""

    def test_model_file_loads_a_urdf_beside_it(self):
        from gencoord.generate.load import load_model
        with tempfile.TemporaryDirectory(prefix="gencoord-urdf-") as folder:
            Path(folder, "two.urdf").write_text(TWO_LINKS, encoding="utf-8")
            Path(folder, "arm.py").write_text(textwrap.dedent("""\
                from gencoord import Model, load_urdf
                model = Model(dim=3)
                links = load_urdf(model, "two.urdf")
                model.joint_spring(links.coordinates["elbow"], 3.0, rest=1.0)
                """), encoding="utf-8")
            model, name, _ = load_model(str(Path(folder, "arm.py")))
        self.assertEqual(name, "arm")
        self.assertEqual([c.name for c in model.coordinates], ["shoulder", "elbow"])
        self.assertEqual(len(model.generalized_forces), 2)


if __name__ == "__main__":
    unittest.main()
