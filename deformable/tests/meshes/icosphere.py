#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes icosphere.obj, a coarse sphere for the .obj tests: the icosahedron inscribed in the
unit sphere, each triangle cut into four, the new vertices pushed out onto the sphere
(42 vertices, 80 triangles, normals outward), centred at (0.2, -0.1, 0.3).

    python3 deformable/tests/meshes/icosphere.py > deformable/tests/meshes/icosphere.obj
"""
import math

CENTER = (0.2, -0.1, 0.3)


def unit(p):
    n = math.sqrt(sum(c * c for c in p))
    return tuple(c / n for c in p)


def icosahedron():
    t = (1 + math.sqrt(5)) / 2
    points = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0),
              (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
              (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
             (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
             (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
             (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    return [unit(p) for p in points], faces


def subdivide(points, faces):
    middle = {}

    def midpoint(a, b):
        key = (min(a, b), max(a, b))
        if key not in middle:
            points.append(unit(tuple((x + y) / 2 for x, y in zip(points[a], points[b]))))
            middle[key] = len(points) - 1
        return middle[key]

    out = []
    for a, b, c in faces:
        ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
        out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    return points, out


def main():
    points, faces = subdivide(*icosahedron())
    print("# icosphere: the icosahedron subdivided once, radius 1, centre %g %g %g" % CENTER)
    print("# written by deformable/tests/meshes/icosphere.py")
    print("o icosphere")
    for p in points:
        print("v %.17g %.17g %.17g" % tuple(c + o for c, o in zip(p, CENTER)))
    for f in faces:
        print("f %d %d %d" % tuple(i + 1 for i in f))


if __name__ == "__main__":
    main()
