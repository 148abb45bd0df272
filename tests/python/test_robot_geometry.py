# SPDX-License-Identifier: BSD-3-Clause
"""A URDF robot's shapes in the viewer's scene (robot_geometry.py): boxes, cylinders, spheres
and STL and OBJ meshes posed with their bodies, meshes found through package:// folders, a
skeleton where a link has nothing to draw, and the base welded to the world. Each shape's
pose, put where the viewer puts its body (the point masses' mean, turned by the body's
rotation), must be the URDF's pose of the <visual>: the link's frame at q times the visual's
origin, at random q."""

from __future__ import annotations

import base64
import math
import random
import struct
import tempfile
import unittest
from array import array
from pathlib import Path

import sympy as sp

from gencoord import Model, load_urdf
from gencoord.dsl.frames import Frame
from gencoord.viewer.mesh_files import read_triangles, resolve
from gencoord.viewer.scene import scene

INERTIA = '<inertia ixx="0.02" iyy="0.03" izz="0.015" ixy="0.001" ixz="0" iyz="0"/>'
URDF = f"""<robot name="drawn">
  <link name="base"><visual><origin xyz="0 0 0.05"/><geometry><box size="0.2 0.2 0.1"/>
    </geometry></visual></link>
  <link name="upper"><inertial><mass value="2"/><origin xyz="0.01 0 -0.2" rpy="0.1 0 0.3"/>
    {INERTIA}</inertial>
    <visual><origin xyz="0 0 -0.2" rpy="0.2 0.1 0"/><geometry><cylinder radius="0.04"
      length="0.4"/></geometry></visual>
    <visual><origin xyz="0.05 0 0"/><geometry><sphere radius="0.06"/></geometry></visual>
  </link>
  <link name="lower"><inertial><mass value="1"/><origin xyz="0 0 -0.15"/>{INERTIA}</inertial>
    <visual><origin xyz="0 0.01 -0.1" rpy="0 0.4 0"/><geometry>
      <mesh filename="package://parts/meshes/wedge.stl" scale="2 2 2"/></geometry></visual>
  </link>
  <link name="hand"><inertial><mass value="0.5"/>{INERTIA}</inertial>
    <visual><geometry><mesh filename="hand.obj"/></geometry></visual>
    <visual><origin xyz="0 0 -0.02" rpy="0 0 0.3"/><geometry>
      <mesh filename="package://parts/meshes/palm.dae" scale="0.5 0.5 0.5"/></geometry></visual>
  </link>
  <link name="finger"><inertial><mass value="0.1"/>{INERTIA}</inertial>
    <visual><geometry><mesh filename="package://parts/missing.stl"/></geometry></visual></link>
  <link name="tip"><visual><geometry><box size="0.01 0.02 0.03"/></geometry></visual></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/><limit lower="-2" upper="2"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="lower"/>
    <origin xyz="0 0 -0.4" rpy="0 0 0.5"/><axis xyz="1 0 0"/><limit lower="-2" upper="2"/>
  </joint>
  <joint name="wrist" type="continuous"><parent link="lower"/><child link="hand"/>
    <origin xyz="0 0 -0.3"/><axis xyz="0 0 1"/></joint>
  <joint name="knuckle" type="continuous"><parent link="hand"/><child link="finger"/>
    <origin xyz="0.1 0 -0.05"/><axis xyz="0 1 0"/></joint>
  <joint name="tip_weld" type="fixed"><parent link="finger"/><child link="tip"/>
    <origin xyz="0 0 -0.04"/></joint>
</robot>
"""
WEDGE = [(0, 0, 0), (0.1, 0, 0), (0, 0.1, 0), (0, 0, 0.1)]
FACES = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def binary_stl(path: Path) -> None:
    body = b"".join(struct.pack("<12fH", 0, 0, 0, *WEDGE[a], *WEDGE[b], *WEDGE[c], 0)
                    for a, b, c in FACES)
    path.write_bytes(b"solid but binary".ljust(80) + struct.pack("<I", len(FACES)) + body)


def obj(path: Path) -> None:
    path.write_text("# a wedge\n" + "".join(f"v {x} {y} {z}\n" for x, y, z in WEDGE)
                    + "f 1 3 2\nf 1/1 2/2 4/4\nf 1//1 4//1 3//1 2//1\n")


def collada(path: Path) -> None:
    """The wedge in millimetres, z up, as COLLADA triangles."""
    positions = " ".join(f"{1000 * c:g}" for corner in WEDGE for c in corner)
    indices = " ".join(str(i) for face in FACES for i in face)
    path.write_text(f"""<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema">
  <asset><unit meter="0.001"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries><geometry id="wedge"><mesh>
    <source id="p"><float_array id="a" count="12">{positions}</float_array></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <triangles count="4"><input semantic="VERTEX" source="#v" offset="0"/><p>{indices}</p>
    </triangles></mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node><instance_geometry url="#wedge"/></node>
  </visual_scene></library_visual_scenes>
</COLLADA>""")


def matrix(pose: list[float]) -> sp.Matrix:
    return sp.Matrix(4, 4, pose)


def homogeneous(frame: Frame) -> sp.Matrix:
    return sp.Matrix(sp.BlockMatrix([[frame.rotation, frame.origin],
                                     [sp.zeros(1, 3), sp.ones(1, 1)]]))


class RobotGeometryTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.TemporaryDirectory(prefix="gencoord-robot-geometry-")
        root = Path(cls.folder.name)
        (root / "robot").mkdir()
        (root / "packages" / "parts" / "meshes").mkdir(parents=True)
        cls.urdf = root / "robot" / "drawn.urdf"
        cls.urdf.write_text(URDF, encoding="utf-8")
        binary_stl(root / "packages" / "parts" / "meshes" / "wedge.stl")
        obj(root / "robot" / "hand.obj")
        collada(root / "packages" / "parts" / "meshes" / "palm.dae")
        cls.packages = [str(root / "packages")]
        cls.model = Model(dim=3)
        cls.links = load_urdf(cls.model, str(cls.urdf))
        cls.scene = scene(cls.model, "drawn", packages=cls.packages)
        cls.bodies = {body["name"]: body for body in cls.scene["bodies"]}

    @classmethod
    def tearDownClass(cls):
        cls.folder.cleanup()

    def test_each_link_is_drawn_as_its_visuals_or_its_skeleton(self):
        kinds = {name: [v["kind"] for v in body["visuals"]] for name, body in self.bodies.items()}
        # the finger's mesh is missing: a capsule to its child's joint; the tip, massless and
        # welded to the finger, rides on it
        self.assertEqual(kinds, {"upper": ["cylinder", "sphere"], "lower": ["mesh"],
                                 "hand": ["mesh", "mesh"], "finger": ["capsule", "box"]})
        self.assertEqual([v["kind"] for v in self.scene["world_visuals"]], ["box"])
        self.assertEqual(self.scene["world_visuals"][0]["size"], [0.2, 0.2, 0.1])

    def test_meshes_carry_their_scaled_triangles(self):
        (wedge,) = self.bodies["lower"]["visuals"]
        corners = array("f", base64.b64decode(wedge["triangles"])).tolist()
        self.assertEqual(len(corners), 4 * 9)
        self.assertAlmostEqual(max(corners), 0.2, places=6)  # scale 2
        hand, palm = self.bodies["hand"]["visuals"]
        self.assertEqual(len(array("f", base64.b64decode(hand["triangles"]))), 4 * 9)
        # COLLADA in millimetres, then the URDF's scale
        corners = array("f", base64.b64decode(palm["triangles"])).tolist()
        self.assertEqual(len(corners), 4 * 9)
        self.assertAlmostEqual(max(corners), 0.05, places=6)

    def test_poses_put_every_shape_where_the_urdf_does(self):
        rng = random.Random(3)
        q = [c.symbol for c in self.model.coordinates]
        for _ in range(3):
            values = {symbol: rng.uniform(-1.5, 1.5) for symbol in q}
            for body in self.model.bodies:
                drawn = self.bodies[body.name]["visuals"]
                link = self.links[body.name]
                expected = [homogeneous(link.frame * g.origin.frame()) for g in link.geometry
                            if g.kind == "visual" and g.attributes.get("filename")
                            != "package://parts/missing.stl"]
                if body.name == "finger":  # the tip's box, on the finger's body
                    tip = self.links["tip"]
                    expected = [homogeneous(tip.frame * tip.geometry[0].origin.frame())]
                    drawn = drawn[1:]
                mean = sum((point.position for point in body.particles),
                           sp.zeros(3, 1)) / len(body.particles)
                placed = homogeneous(Frame(body.frame.rotation, mean))
                self.assertEqual(len(drawn), len(expected), body.name)
                for shape, truth in zip(drawn, expected):
                    error = (placed * matrix(shape["pose"]) - truth).subs(values)
                    self.assertLess(max(abs(float(e)) for e in error), 1e-10, body.name)

    def test_the_skeleton_joins_a_link_to_its_childrens_joints(self):
        # the upper arm without its visuals: one capsule from the shoulder to the elbow (0.4 m)
        model = Model(dim=3)
        bare = self.urdf.with_name("bare.urdf")
        text = URDF.split('<link name="upper">')[1].split("</link>")[0]
        bare.write_text(URDF.replace(text, text.split("<visual>")[0]), encoding="utf-8")
        load_urdf(model, str(bare))
        upper = next(b for b in scene(model, "bare")["bodies"] if b["name"] == "upper")
        (capsule,) = upper["visuals"]
        self.assertEqual(capsule["kind"], "capsule")
        self.assertAlmostEqual(capsule["length"], 0.4)
        self.assertAlmostEqual(capsule["radius"], 0.04)

    def test_mesh_files_resolve_and_read(self):
        robot = str(self.urdf)
        self.assertIsNone(resolve("package://parts/nowhere.stl", robot, self.packages))
        self.assertIsNone(resolve("hand.dae", robot, []))
        self.assertTrue(resolve("hand.obj", robot, []).endswith("hand.obj"))
        ascii_stl = self.urdf.with_name("one.stl")
        ascii_stl.write_text("solid one\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
                             "   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n endfacet\n"
                             "endsolid one\n")
        self.assertEqual(read_triangles(str(ascii_stl)), [0, 0, 0, 1, 0, 0, 0, 1, 0])
        broken = self.urdf.with_name("broken.obj")
        broken.write_text("v 0 0 0\nf 1 2 3\n")
        self.assertIsNone(read_triangles(str(broken)))

    def test_models_without_a_urdf_keep_their_shapes(self):
        model = Model(dim=2)
        theta = model.coordinate("theta")
        model.particle("bob", 1.0, [sp.sin(theta), -sp.cos(theta)])
        drawn = scene(model, "pendulum")
        self.assertNotIn("world_visuals", drawn)
        self.assertTrue(all(math.isfinite(p["mass"]) for p in drawn["particles"]))


if __name__ == "__main__":
    unittest.main()
