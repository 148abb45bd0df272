# SPDX-License-Identifier: BSD-3-Clause
"""Triangles of a COLLADA (.dae) file, the mesh format most ROS robot packages ship their
visuals in, read for the viewer.

What is read: the geometries that the file's scene instantiates (its <scene>'s visual scene,
else the first one; a file without one gives every geometry once), through the transforms of
the nodes above them (<matrix>, <translate>, <rotate>, <scale>, in document order, and nodes
instantiated from <library_nodes>); each geometry's <triangles>, <polylist> and <polygons>
(polygons split into fans; their holes and <lines> are not drawn). The corners are then
scaled to metres by the <asset>'s <unit meter> and turned so that its <up_axis> (Y_UP when
the file names none, as the format says) is the link's z. Materials, normals, texture
coordinates, cameras, lights and animations are not read.

A file that is not such a COLLADA document, holds a transform the viewer does not read
(<lookat>, <skew>), an index or a reference to nothing, a number that is not finite, or more
than `max_triangles` triangles gives None: the viewer then draws the link's skeleton.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

Matrix = list[list[float]]  # 4 x 4, row-major, acting on column vectors

_IDENTITY: Matrix = [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]
# the rotation that takes the file's up axis to z
_UP_AXIS: dict[str, Matrix] = {
    "Z_UP": _IDENTITY,
    "Y_UP": [[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, -1.0, 0.0], [0.0, 1.0, 0.0, 0.0],
             [0.0, 0.0, 0.0, 1.0]],
    "X_UP": [[0.0, 0.0, -1.0, 0.0], [0.0, 1.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0],
             [0.0, 0.0, 0.0, 1.0]],
}
_MAX_NODE_DEPTH = 64  # deeper nesting, or a node that instantiates itself, is refused
_MAX_NODE_VISITS = 100_000  # nodes that instantiate others twice over, nested, multiply


class _Unreadable(Exception):
    """The file is not one the viewer can draw."""


def collada_triangles(data: bytes, max_triangles: int) -> list[float] | None:
    """The triangles' corners (x, y, z per corner, three corners per triangle) in metres in
    z-up axes, or None where the file cannot be drawn (see the module's comment)."""
    try:
        root = ET.fromstring(data)
    except (ET.ParseError, ValueError):
        return None
    try:
        return _Document(root, max_triangles).triangles()
    except (_Unreadable, ValueError, IndexError, KeyError, OverflowError):
        return None


def _local(element: ET.Element) -> str:
    """The tag without its namespace (COLLADA 1.4 and 1.5 differ only there)."""
    return element.tag.rsplit("}", 1)[-1]


def _children(element: ET.Element, name: str) -> list[ET.Element]:
    return [child for child in element if _local(child) == name]


def _child(element: ET.Element, name: str) -> ET.Element | None:
    return next(iter(_children(element, name)), None)


def _numbers(element: ET.Element, count: int | None = None) -> list[float]:
    values = [float(word) for word in (element.text or "").split()]
    if count is not None and len(values) != count:
        raise _Unreadable(f"<{_local(element)}> holds {len(values)} numbers, not {count}")
    if not all(math.isfinite(value) for value in values):
        raise _Unreadable(f"<{_local(element)}> holds a number that is not finite")
    return values


def _integers(element: ET.Element | None) -> list[int]:
    return [int(word) for word in ((element.text or "") if element is not None else "").split()]


def _scaling(x: float, y: float, z: float) -> Matrix:
    return [[x, 0.0, 0.0, 0.0], [0.0, y, 0.0, 0.0], [0.0, 0.0, z, 0.0], [0.0, 0.0, 0.0, 1.0]]


def _product(a: Matrix, b: Matrix) -> Matrix:
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def _transform(element: ET.Element) -> Matrix | None:
    """The matrix of one of a node's transform elements; None for an element that is not a
    transform."""
    kind = _local(element)
    if kind == "matrix":
        values = _numbers(element, 16)
        return [values[4 * i:4 * i + 4] for i in range(4)]
    if kind == "translate":
        x, y, z = _numbers(element, 3)
        return [[1.0, 0.0, 0.0, x], [0.0, 1.0, 0.0, y], [0.0, 0.0, 1.0, z], [0.0, 0.0, 0.0, 1.0]]
    if kind == "scale":
        return _scaling(*_numbers(element, 3))
    if kind == "rotate":
        x, y, z, degrees = _numbers(element, 4)
        norm = math.sqrt(x * x + y * y + z * z)
        if norm == 0.0:
            raise _Unreadable("<rotate> about a zero axis")
        x, y, z = x / norm, y / norm, z / norm
        c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
        t = 1.0 - c
        return [[t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0.0],
                [t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0.0],
                [t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0.0],
                [0.0, 0.0, 0.0, 1.0]]
    if kind in ("lookat", "skew"):
        raise _Unreadable(f"<{kind}> is not read")
    return None


class _Document:
    def __init__(self, root: ET.Element, max_triangles: int):
        if _local(root) != "COLLADA":
            raise _Unreadable("not a COLLADA document")
        self.root = root
        self.max_triangles = max_triangles
        self.ids = {element.get("id"): element for element in root.iter() if element.get("id")}
        self.corners: list[float] = []
        self.visits = 0
        self.sources: dict[int, list[list[float]]] = {}  # id(<source>): its positions

    def triangles(self) -> list[float] | None:
        asset = _child(self.root, "asset")
        unit = _child(asset, "unit") if asset is not None else None
        metres = float(unit.get("meter", "1")) if unit is not None else 1.0
        up = _child(asset, "up_axis") if asset is not None else None
        up_axis = (up.text or "").strip() if up is not None else "Y_UP"
        if not math.isfinite(metres) or metres <= 0.0 or up_axis not in _UP_AXIS:
            return None
        top = _product(_UP_AXIS[up_axis], _scaling(metres, metres, metres))
        scene = self._visual_scene()
        if scene is None:
            for geometries in _children(self.root, "library_geometries"):
                for geometry in _children(geometries, "geometry"):
                    self._add_geometry(geometry, top)
        else:
            for node in _children(scene, "node"):
                self._add_node(node, top, 0)
        if not all(math.isfinite(value) for value in self.corners):
            return None  # a transform that overflows
        return self.corners or None

    def _visual_scene(self) -> ET.Element | None:
        scene = _child(self.root, "scene")
        instance = _child(scene, "instance_visual_scene") if scene is not None else None
        if instance is not None:
            return self._referenced(instance, "visual_scene")
        for library in _children(self.root, "library_visual_scenes"):
            for visual_scene in _children(library, "visual_scene"):
                return visual_scene
        return None

    def _referenced(self, element: ET.Element, kind: str, attribute: str = "url") -> ET.Element:
        """The element of `kind` that an instance's url="#id" (an input's source="#id") names."""
        url = element.get(attribute, "")
        target = self.ids.get(url[1:]) if url.startswith("#") else None
        if target is None or _local(target) != kind:
            raise _Unreadable(f"{url!r} names no <{kind}>")
        return target

    def _add_node(self, node: ET.Element, parent: Matrix, depth: int) -> None:
        self.visits += 1
        if depth > _MAX_NODE_DEPTH or self.visits > _MAX_NODE_VISITS:
            raise _Unreadable("nodes nested too deep, or instantiated too often")
        pose = parent
        for element in node:
            transform = _transform(element)
            if transform is not None:
                pose = _product(pose, transform)
        for element in node:
            kind = _local(element)
            if kind == "instance_geometry":
                self._add_geometry(self._referenced(element, "geometry"), pose)
            elif kind == "instance_node":
                self._add_node(self._referenced(element, "node"), pose, depth + 1)
            elif kind == "node":
                self._add_node(element, pose, depth + 1)

    def _add_geometry(self, geometry: ET.Element, pose: Matrix) -> None:
        mesh = _child(geometry, "mesh")
        if mesh is None:  # a spline or a convex mesh: nothing to draw
            return
        placed: dict[int, list[list[float]]] = {}  # id(<source>): its positions at `pose`
        for primitive in mesh:
            kind = _local(primitive)
            if kind in ("triangles", "polylist", "polygons"):
                self._add_primitive(primitive, kind, pose, placed)

    def _positions(self, primitive: ET.Element) -> tuple[ET.Element, int, int]:
        """The <source> of the positions a primitive's VERTEX input names, that input's offset
        and the number of indices per corner."""
        inputs = _children(primitive, "input")
        if not inputs:
            raise _Unreadable("a primitive without inputs")
        stride = max(int(element.get("offset", "0")) for element in inputs) + 1
        vertex = next((element for element in inputs if element.get("semantic") == "VERTEX"),
                      None)
        if vertex is None:
            raise _Unreadable("a primitive without a VERTEX input")
        vertices = self._referenced(vertex, "vertices", "source")
        position = next((element for element in _children(vertices, "input")
                         if element.get("semantic") == "POSITION"), None)
        if position is None:
            raise _Unreadable("<vertices> without a POSITION input")
        source = self._referenced(position, "source", "source")
        return source, int(vertex.get("offset", "0")), stride

    def _read_positions(self, source: ET.Element) -> list[list[float]]:
        if id(source) in self.sources:
            return self.sources[id(source)]
        array = _child(source, "float_array")
        if array is None:
            raise _Unreadable("a <source> without a <float_array>")
        values = _numbers(array)
        technique = _child(source, "technique_common")
        accessor = _child(technique, "accessor") if technique is not None else None
        stride = int(accessor.get("stride", "3")) if accessor is not None else 3
        offset = int(accessor.get("offset", "0")) if accessor is not None else 0
        if stride < 3 or offset < 0:
            raise _Unreadable("positions of fewer than three numbers")
        positions = [values[k:k + 3] for k in range(offset, len(values) - 2, stride)]
        self.sources[id(source)] = positions
        return positions

    def _add_primitive(self, primitive: ET.Element, kind: str, pose: Matrix,
                       placed: dict[int, list[list[float]]]) -> None:
        source, offset, stride = self._positions(primitive)
        if kind == "polygons":
            polygons = [_integers(p) for p in _children(primitive, "p")]
        else:
            indices = _integers(_child(primitive, "p"))
            counts = (_integers(_child(primitive, "vcount")) if kind == "polylist"
                      else [3] * (len(indices) // (3 * stride)))
            polygons, start = [], 0
            for count in counts:
                if count < 0:
                    raise _Unreadable("a polygon of a negative count")
                polygons.append(indices[start:start + count * stride])
                start += count * stride
            if start != len(indices):
                raise _Unreadable("<p> does not hold the corners its counts say")
        if id(source) not in placed:
            placed[id(source)] = [_apply(pose, point) for point in self._read_positions(source)]
        points = placed[id(source)]
        for polygon in polygons:
            if len(polygon) % stride:
                raise _Unreadable("a polygon whose indices are not whole corners")
            indices = polygon[offset::stride]
            if not all(0 <= index < len(points) for index in indices):
                raise _Unreadable("an index that names no position")
            corners = [points[index] for index in indices]
            for k in range(1, len(corners) - 1):
                if len(self.corners) // 9 >= self.max_triangles:
                    raise _Unreadable("more triangles than the page embeds")
                for corner in (corners[0], corners[k], corners[k + 1]):
                    self.corners.extend(corner)


def _apply(pose: Matrix, point: list[float]) -> list[float]:
    x, y, z = point
    return [pose[i][0] * x + pose[i][1] * y + pose[i][2] * z + pose[i][3] for i in range(3)]
