# SPDX-License-Identifier: BSD-3-Clause
"""Property test of the COLLADA reader of the viewer (Hypothesis): a good file (a square as a
polylist, a triangle list and a polygon, placed by nodes with every transform it reads and a
node from the node library, in millimetres) with up to three mutations (an element's text or
an attribute replaced by junk: not a number, not finite, too large, the wrong count, an index
or a reference to nothing; an element taken out) gives finite triangles in metres or None
(the viewer then draws the link's skeleton), never an exception, and soon. Run by CTest as
`property_tests` (see test_urdf_fuzz.py).
"""

from __future__ import annotations

import math
import time
import unittest
import xml.etree.ElementTree as ET

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gencoord.viewer.collada import collada_triangles

NAMESPACE = "http://www.collada.org/2005/11/COLLADASchema"
GOOD = f"""<COLLADA xmlns="{NAMESPACE}" version="1.4.1">
  <asset><unit meter="0.001"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries><geometry id="square"><mesh>
    <source id="positions">
      <float_array id="array" count="12">0 0 0 1000 0 0 1000 1000 0 0 1000 0</float_array>
      <technique_common><accessor source="#array" count="4" stride="3"/></technique_common></source>
    <vertices id="vertices"><input semantic="POSITION" source="#positions"/></vertices>
    <polylist count="1"><input semantic="VERTEX" source="#vertices" offset="0"/>
      <vcount>4</vcount><p>0 1 2 3</p></polylist>
    <triangles count="2"><input semantic="VERTEX" source="#vertices" offset="0"/>
      <p>0 1 2 0 2 3</p></triangles>
    <polygons count="1"><input semantic="VERTEX" source="#vertices" offset="0"/>
      <p>0 1 2 3</p></polygons>
  </mesh></geometry></library_geometries>
  <library_nodes><node id="part"><scale>2 2 2</scale>
    <instance_geometry url="#square"/></node></library_nodes>
  <library_visual_scenes><visual_scene id="scene">
    <node id="placed"><translate>0 0 500</translate><rotate>0 0 1 90</rotate>
      <matrix>1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1</matrix>
      <instance_geometry url="#square"/><node id="inner"><instance_node url="#part"/></node>
    </node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>"""
JUNK = st.sampled_from(["", "x", "nan", "inf", "-inf", "1e400", "-1", "0", "4", "99",
                        "2147483648", "1 2", "0 0 0 0", "1e308 1e308 1e308", "#square",
                        "#nowhere", "#scene", "#part", "#placed", "#vertices", "VERTEX",
                        "POSITION", "Y_UP", "W_UP", "0 1 2 3 4 5 6 7", "-5 0 1"])
LIMIT = 1000


ET.register_namespace("", NAMESPACE)  # the mutated files keep COLLADA's own prefix-free tags


@st.composite
def mutated(draw) -> bytes:
    root = ET.fromstring(GOOD)
    for _ in range(draw(st.integers(min_value=1, max_value=3))):
        elements = list(root.iter())
        element = elements[draw(st.integers(min_value=0, max_value=len(elements) - 1))]
        action = draw(st.sampled_from(["text", "attribute", "remove"]))
        if action == "text":
            element.text = draw(JUNK)
        elif action == "attribute" and element.attrib:
            name = draw(st.sampled_from(sorted(element.attrib)))
            element.set(name, draw(JUNK))
        elif action == "remove" and element is not root:
            parent = next(p for p in root.iter() if element in list(p))
            parent.remove(element)
    return ET.tostring(root)


class ColladaFuzzTest(unittest.TestCase):

    def test_the_good_file_is_read(self):
        corners = collada_triangles(GOOD.encode(), LIMIT)
        self.assertEqual(len(corners), 2 * 3 * 2 * 9)  # placed twice: 3 primitives of 2 triangles
        self.assertAlmostEqual(max(abs(c) for c in corners), 2.0)  # the scaled part, in m

    @settings(max_examples=400, deadline=None, derandomize=True,
              suppress_health_check=[HealthCheck.too_slow])
    @given(mutated())
    def test_a_mutated_file_gives_finite_triangles_or_none(self, data: bytes):
        start = time.process_time()
        corners = collada_triangles(data, LIMIT)
        self.assertLess(time.process_time() - start, 2.0)
        if corners is not None:
            self.assertTrue(corners and len(corners) % 9 == 0, data)
            self.assertLessEqual(len(corners) // 9, LIMIT)
            self.assertTrue(all(math.isfinite(c) for c in corners), data)


if __name__ == "__main__":
    unittest.main()
