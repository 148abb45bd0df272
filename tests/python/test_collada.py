# SPDX-License-Identifier: BSD-3-Clause
"""COLLADA (.dae) visuals for the viewer (gencoord/viewer/collada.py): a polylist, a
triangles and a polygons primitive placed by their nodes' transforms, scaled by the file's
unit and turned by its up axis, against corners worked out by hand; and the files it cannot
draw, each giving None (the viewer's skeleton) rather than an exception or a wrong mesh."""

from __future__ import annotations

import tempfile
import time
import unittest
from pathlib import Path

from gencoord.viewer.collada import collada_triangles
from gencoord.viewer.mesh_files import read_triangles

# a unit square in millimetres (1000 x 1000), its normal on a second index
SQUARE = """
    <geometry id="square" name="square"><mesh>
      <source id="square-positions">
        <float_array id="square-array" count="12">0 0 0 1000 0 0 1000 1000 0 0 1000 0
        </float_array>
        <technique_common><accessor source="#square-array" count="4" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common>
      </source>
      <source id="square-normals">
        <float_array id="square-normal-array" count="3">0 0 1</float_array>
        <technique_common><accessor source="#square-normal-array" count="1" stride="3"/>
        </technique_common></source>
      <vertices id="square-vertices">
        <input semantic="POSITION" source="#square-positions"/></vertices>
      {primitive}
    </mesh></geometry>"""
POLYLIST = """<polylist count="1">
        <input semantic="VERTEX" source="#square-vertices" offset="0"/>
        <input semantic="NORMAL" source="#square-normals" offset="1"/>
        <vcount>4</vcount><p>0 0 1 0 2 0 3 0</p></polylist>"""
TRIANGLES = """<triangles count="2">
        <input semantic="VERTEX" source="#square-vertices" offset="0"/>
        <input semantic="NORMAL" source="#square-normals" offset="1"/>
        <p>0 0 1 0 2 0 0 0 2 0 3 0</p></triangles>"""
POLYGONS = """<polygons count="1">
        <input semantic="VERTEX" source="#square-vertices" offset="0"/>
        <p>0 1 2 3</p></polygons>"""


def document(primitive: str = POLYLIST, *,
             asset: str = "<unit meter=\"0.001\"/><up_axis>Z_UP</up_axis>",
             node: str = "<translate>0 0 500</translate><rotate>0 0 1 90</rotate>"
                         "<instance_geometry url=\"#square\"/>",
             libraries: str = "", namespace: str = "http://www.collada.org/2005/11/COLLADASchema"
             ) -> bytes:
    return f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="{namespace}" version="1.4.1">
  <asset>{asset}</asset>
  <library_geometries>{SQUARE.format(primitive=primitive)}</library_geometries>
  {libraries}
  <library_visual_scenes><visual_scene id="scene"><node id="placed">{node}</node></visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>""".encode()


def corners_of(flat: list[float]) -> list[tuple[float, ...]]:
    return [tuple(round(value, 12) + 0.0 for value in flat[k:k + 3])
            for k in range(0, len(flat), 3)]


# the square turned 90 degrees about z, raised by 0.5 m, in metres, as two fan triangles
TURNED_AND_RAISED = [(0, 0, 0.5), (0, 1, 0.5), (-1, 1, 0.5),
                     (0, 0, 0.5), (-1, 1, 0.5), (-1, 0, 0.5)]


class ColladaTest(unittest.TestCase):

    def test_primitives_are_placed_by_their_nodes_and_scaled_to_metres(self):
        for primitive in (POLYLIST, TRIANGLES, POLYGONS):
            with self.subTest(primitive=primitive.split()[0]):
                self.assertEqual(corners_of(collada_triangles(document(primitive), 100)),
                                 TURNED_AND_RAISED)

    def test_collada_1_5_reads_the_same(self):
        data = document(namespace="http://www.collada.org/2008/03/COLLADASchema")
        self.assertEqual(corners_of(collada_triangles(data, 100)), TURNED_AND_RAISED)

    def test_the_up_axis_becomes_z(self):
        # a point up the file's y is up the link's z; no up_axis means Y_UP
        plain = "<instance_geometry url=\"#square\"/>"
        for asset in ("<up_axis>Y_UP</up_axis>", ""):
            with self.subTest(asset=asset):
                corners = corners_of(collada_triangles(document(asset=asset, node=plain), 100))
                self.assertEqual(corners[1], (1000, 0, 0))
                self.assertEqual(corners[2], (1000, 0, 1000))
        corners = corners_of(collada_triangles(
            document(asset="<up_axis>X_UP</up_axis>", node=plain), 100))
        self.assertEqual(corners[1], (0, 0, 1000))  # the file's x is up

    def test_matrices_and_nodes_from_the_node_library(self):
        # the same pose as a row-major matrix, on a node that the scene instantiates
        library = """<library_nodes><node id="part">
            <matrix>0 -1 0 0  1 0 0 0  0 0 1 500  0 0 0 1</matrix>
            <instance_geometry url="#square"/></node></library_nodes>"""
        data = document(libraries=library, node="<instance_node url=\"#part\"/>")
        self.assertEqual(corners_of(collada_triangles(data, 100)), TURNED_AND_RAISED)

    def test_a_file_without_a_scene_gives_each_geometry_once(self):
        data = (b"<COLLADA xmlns='http://www.collada.org/2005/11/COLLADASchema'>"
                b"<asset><up_axis>Z_UP</up_axis></asset><library_geometries>"
                + SQUARE.format(primitive=POLYGONS).encode() + b"</library_geometries></COLLADA>")
        self.assertEqual(len(collada_triangles(data, 100)), 2 * 9)

    def test_files_it_cannot_draw_give_none(self):
        bomb = ("<?xml version='1.0'?><!DOCTYPE COLLADA [<!ENTITY a 'aaaaaaaaaa'>"
                + "".join(f"<!ENTITY {chr(98 + k)} '{('&' + chr(97 + k) + ';') * 10}'>"
                          for k in range(9))
                + "]><COLLADA>&j;</COLLADA>").encode()
        doubling = "".join(
            f"<node id='n{k}'><instance_node url='#n{k + 1}'/><instance_node url='#n{k + 1}'/>"
            "</node>" for k in range(40)) + "<node id='n40'/>"
        cases = {
            "malformed XML": document()[:-20],
            "another document": b"<robot name='r'/>",
            "an index past the positions": document(POLYLIST.replace("3 0</p>", "4 0</p>")),
            "a negative index": document(POLYLIST.replace("3 0</p>", "-1 0</p>")),
            "counts the indices do not fill": document(POLYLIST.replace("<vcount>4", "<vcount>5")),
            "a reference to nothing": document(node="<instance_geometry url=\"#cube\"/>"),
            "a number that is not finite": document().replace(b">0 0 0 1000", b">0 0 0 nan"),
            "a transform it does not read": document(node="<lookat>0 0 1 0 0 0 0 1 0</lookat>"
                                                          "<instance_geometry url=\"#square\"/>"),
            "a rotation about no axis": document(node="<rotate>0 0 0 90</rotate>"
                                                      "<instance_geometry url=\"#square\"/>"),
            "a node that instantiates itself": document(
                libraries="<library_nodes><node id='loop'><instance_node url='#loop'/></node>"
                          "</library_nodes>", node="<instance_node url=\"#loop\"/>"),
            "nodes that instantiate twice over": document(
                libraries=f"<library_nodes>{doubling}</library_nodes>",
                node="<instance_node url=\"#n0\"/>"),
            "a transform that overflows": document(
                asset="<up_axis>Z_UP</up_axis>",
                node="<scale>1e308 1 1</scale><instance_geometry url=\"#square\"/>"),
            "an unknown up axis": document(asset="<up_axis>W_UP</up_axis>"),
            "a unit of no length": document(asset="<unit meter=\"0\"/>"),
            "an entity bomb": bomb,
        }
        for name, data in cases.items():
            with self.subTest(name):
                self.assertNotEqual(data, document(), "the case changes nothing")
                start = time.process_time()
                self.assertIsNone(collada_triangles(data, 100))
                self.assertLess(time.process_time() - start, 5.0)
        self.assertIsNone(collada_triangles(document(), 1))  # more triangles than embedded

    def test_read_triangles_reads_dae_files(self):
        with tempfile.TemporaryDirectory() as folder:
            path = Path(folder) / "square.DAE"
            path.write_bytes(document())
            self.assertEqual(corners_of(read_triangles(str(path))), TURNED_AND_RAISED)


if __name__ == "__main__":
    unittest.main()
