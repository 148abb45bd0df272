# SPDX-License-Identifier: BSD-3-Clause
"""A deformable mass-spring run as a viewer page: the frames and springs that deformable_demo
(deformable/apps/deformable_demo/) writes (frames.csv: frame,time,node,x,y; springs.csv:
spring,i,j,broken_at), played as nodes and springs, each spring gone from the time it broke.

    python3 -m gencoord.viewer.deformable out/brittle-beam   # writes out/brittle-beam/frames.html

The page is the model viewer's (page.py, viewer.js) with a mesh instead of particles; its plot
shows how many springs are intact over time. A run of more than page.MAX_NUMBERS numbers keeps
every k-th frame and the last.
"""

from __future__ import annotations

import argparse
import csv
import math
import os
import sys

from gencoord.tool.errors import ToolError
from gencoord.viewer import page

SCENE = {"format": "gencoord-scene 1", "dim": 2, "up": [0.0, 1.0], "particles": [],
         "fixed_points": [], "bodies": [], "links": [], "planes": [], "pivots": []}


def _rows(path: str, header: list[str]):
    """The rows of a CSV file as lists of text, after checking its header."""
    try:
        with open(path, newline="", encoding="utf-8") as handle:
            reader = csv.reader(handle)
            first = next(reader, None)
            if first != header:
                raise ToolError(f"{path}:1: expected the header {','.join(header)}, got "
                                f"{','.join(first or [])}")
            yield from ((reader.line_num, row) for row in reader if row)
    except FileNotFoundError:
        raise ToolError(f"{path}: no such file; run deformable_demo (scripts/"
                        f"deformable_demo.sh) to write it") from None
    except (csv.Error, UnicodeDecodeError) as error:
        raise ToolError(f"{path}: not a CSV file ({error})") from None


def _number(text: str, path: str, line: int) -> float:
    try:
        return float(text)
    except ValueError:
        raise ToolError(f"{path}:{line}: '{text}' is not a number") from None


def _index(text: str, path: str, line: int) -> int:
    value = _number(text, path, line)
    if not (math.isfinite(value) and value == int(value) and value >= 0):
        raise ToolError(f"{path}:{line}: '{text}' is not a whole number >= 0")
    return int(value)


def deformable_data(folder: str) -> dict:
    """The page data of a deformable run (page.page_data's layout, with a mesh)."""
    frames_csv = os.path.join(folder, "frames.csv")
    springs_csv = os.path.join(folder, "springs.csv")
    times: list[float] = []
    frames: list[list[tuple[float, float]]] = []
    for line, row in _rows(frames_csv, ["frame", "time", "node", "x", "y"]):
        if len(row) != 5:
            raise ToolError(f"{frames_csv}:{line}: expected 5 fields, got {len(row)}")
        frame = _index(row[0], frames_csv, line)
        node = _index(row[2], frames_csv, line)
        if frame == len(frames):
            frames.append([])
            times.append(_number(row[1], frames_csv, line))
        if frame != len(frames) - 1 or node != len(frames[-1]):
            raise ToolError(f"{frames_csv}:{line}: frame {frame}, node {node} out of order")
        frames[-1].append((_number(row[3], frames_csv, line),
                           _number(row[4], frames_csv, line)))
    if not frames or any(len(f) != len(frames[0]) for f in frames):
        raise ToolError(f"{frames_csv}: no frames, or frames with different numbers of nodes")
    nodes = len(frames[0])
    springs = []
    for line, row in _rows(springs_csv, ["spring", "i", "j", "broken_at"]):
        if len(row) != 4:
            raise ToolError(f"{springs_csv}:{line}: expected 4 fields, got {len(row)}")
        i, j = _index(row[1], springs_csv, line), _index(row[2], springs_csv, line)
        if not (0 <= i < nodes and 0 <= j < nodes):
            raise ToolError(f"{springs_csv}:{line}: node {max(i, j)} does not exist "
                            f"({nodes} nodes)")
        springs.append((_number(row[3], springs_csv, line) if row[3] else math.inf, i, j))
    springs.sort(key=lambda spring: -spring[0])  # the intact ones at time t come first
    kept, stride = page.kept_rows(len(frames), 2 * nodes)
    return {
        "scene": dict(SCENE, name=os.path.basename(os.path.abspath(folder))),
        "source": "frames.csv",
        "rows": len(frames), "stride": stride, "frames": len(kept),
        "coordinates": [],
        "points": [str(n) for n in range(nodes)],
        "mesh": {"springs": len(springs),
                 "broken": sum(1 for s in springs if s[0] < math.inf)},
        "arrays": {
            "t": page.encoded([times[k] for k in kept], "d"),
            "positions": page.encoded(
                [c for k in kept for node in frames[k] for c in node], "f"),
            # node pairs, latest broken first; the time each broke (a huge number if never)
            "spring_nodes": page.encoded([n for s in springs for n in s[1:]], "i"),
            "broken_at": page.encoded([min(s[0], 1e300) for s in springs], "d"),
        },
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", help="where deformable_demo wrote frames.csv and springs.csv")
    parser.add_argument("-o", "--output", help="the page (default: FOLDER/frames.html)")
    args = parser.parse_args(argv)
    html = args.output or os.path.join(args.folder, "frames.html")
    try:
        data = deformable_data(args.folder)
        page.write_data_page(data, html, data["scene"]["name"])
    except (ToolError, OSError) as error:
        print(f"view: error: {error}", file=sys.stderr)
        return 1
    print(html)
    return 0


if __name__ == "__main__":
    sys.exit(main())
