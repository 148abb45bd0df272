# SPDX-License-Identifier: BSD-3-Clause
"""Triangle meshes of URDF visuals, read for the viewer: STL (binary or ASCII), Wavefront
OBJ (vertices and faces; polygons split into fans) and COLLADA (collada.py). Each reader
returns the triangles' corners as one flat list of floats (x, y, z per corner, three corners
per triangle), in the file's own units (COLLADA's in metres, as its file says); a file it
cannot read gives None, and the viewer draws the link's skeleton.

`resolve` finds a URDF's mesh file name: a path relative to the URDF, an absolute path or
file:// URL, or package://<package>/<path> looked up in a search path of folders that hold
the packages (as ROS's ROS_PACKAGE_PATH does).
"""

from __future__ import annotations

import os
import struct
from typing import Sequence

from gencoord.viewer.collada import collada_triangles

MAX_TRIANGLES = 200_000  # a larger mesh is not embedded in the page: the skeleton stands in


def resolve(filename: str, urdf_path: str, package_path: Sequence[str]) -> str | None:
    """The mesh file a URDF names, or None where no such file exists."""
    if filename.startswith("package://"):
        relative = filename[len("package://"):]
        candidates = [os.path.join(folder, relative) for folder in package_path]
    elif filename.startswith("file://"):
        candidates = [filename[len("file://"):]]
    else:
        candidates = [os.path.join(os.path.dirname(os.path.abspath(urdf_path)), filename)]
    return next((path for path in candidates if os.path.isfile(path)), None)


def read_triangles(path: str) -> list[float] | None:
    """The triangles of an .stl, .obj or .dae file, or None for another kind or a broken
    file."""
    extension = os.path.splitext(path)[1].lower()
    try:
        with open(path, "rb") as handle:
            data = handle.read()
    except OSError:
        return None
    if extension == ".stl":
        return _stl(data)
    if extension == ".obj":
        return _obj(data.decode("utf-8", errors="replace"))
    if extension == ".dae":
        return collada_triangles(data, MAX_TRIANGLES)
    return None


def _stl(data: bytes) -> list[float] | None:
    if len(data) >= 84:
        count = struct.unpack_from("<I", data, 80)[0]
        if 84 + 50 * count == len(data):  # binary: the size says so, whatever the header says
            if count > MAX_TRIANGLES:
                return None
            corners: list[float] = []
            for k in range(count):
                corners.extend(struct.unpack_from("<9f", data, 84 + 50 * k + 12))
            return corners
    corners = []  # ASCII: "vertex x y z" lines
    for line in data.decode("ascii", errors="replace").splitlines():
        words = line.split()
        if len(words) == 4 and words[0] == "vertex":
            try:
                corners.extend(float(w) for w in words[1:])
            except ValueError:
                return None
    if not corners or len(corners) % 9 or len(corners) // 9 > MAX_TRIANGLES:
        return None
    return corners


def _obj(text: str) -> list[float] | None:
    vertices: list[tuple[float, ...]] = []
    corners: list[float] = []
    try:
        for line in text.splitlines():
            words = line.split()
            if not words:
                continue
            if words[0] == "v" and len(words) >= 4:
                vertices.append(tuple(float(w) for w in words[1:4]))
            elif words[0] == "f" and len(words) >= 4:
                # "i", "i/t", "i/t/n" or "i//n"; negative indices count from the end
                indices = [int(w.split("/")[0]) for w in words[1:]]
                polygon = [vertices[i - 1 if i > 0 else len(vertices) + i] for i in indices]
                for k in range(1, len(polygon) - 1):
                    for corner in (polygon[0], polygon[k], polygon[k + 1]):
                        corners.extend(corner)
    except (ValueError, IndexError):
        return None
    if not corners or len(corners) // 9 > MAX_TRIANGLES:
        return None
    return corners
