# SPDX-License-Identifier: BSD-3-Clause
"""A trajectory as one self-contained HTML page that plays it in 3D (three.js, inline): the
simulate program's CSV, the model's scene (gencoord/viewer/scene.py) and viewer.js, in one file
that opens in any browser without a server or the network.

    python3 -m gencoord.viewer.page out/double_pendulum.csv generated/double_pendulum.scene.json \\
        out/double_pendulum.html

A cross-check trajectory (`crosscheck --trajectory`) also holds the maximal penalty model's
particles (columns maximal:<particle>_x, ...): the page draws that model beside the reduced
one, faded, with its own copies of the fixed points.

A page holds at most MAX_NUMBERS numbers of trajectory: a longer trajectory keeps every
stride-th state (and its last), and each kept energy error is the largest of those it stands
for, so that the plot still shows the worst drift.
"""

from __future__ import annotations

import argparse
import array
import base64
import json
import math
import os
import string
import sys
import tempfile

from gencoord.tool.errors import ToolError
from gencoord.tool.trajectory_svg import FIXED_PREFIX, energy_error, read_trajectory
from gencoord.viewer import three_js

MAX_NUMBERS = 2_000_000   # 8 MB of float32 before base64: what a browser tab holds at ease
# the prefix of a cross-check trajectory's maximal-model columns (drivers/crosscheck.cpp)
COMPANION = "maximal:"
HERE = os.path.dirname(os.path.abspath(__file__))


def encoded(values, kind: str) -> str:
    """Little-endian float32 ('f'), float64 ('d') or int32 ('i') values as base64."""
    packed = array.array(kind, values)
    if sys.byteorder == "big":
        packed.byteswap()
    return base64.b64encode(packed.tobytes()).decode("ascii")


def kept_rows(count: int, per_row: int) -> tuple[list[int], int]:
    """The rows a page keeps, and the stride between them."""
    stride = max(1, math.ceil(count * per_row / MAX_NUMBERS))
    rows = list(range(0, count, stride))
    if rows[-1] != count - 1:
        rows.append(count - 1)
    return rows, stride


def _worst_in_buckets(values: list[float], rows: list[int]) -> list[float]:
    """For each kept row, the value of largest magnitude from it up to the next kept row."""
    ends = [*rows[1:], len(values)]
    return [max(values[start:max(end, start + 1)], key=abs) for start, end in zip(rows, ends)]


def _side_by_side(trajectory, scene: dict) -> tuple[list[str], list[float]]:
    """Moves a companion model's points (a cross-check trajectory's maximal:<particle>) beside
    the model's, across the up axis, and adds its copies of the fixed points; returns the
    companion's columns and the shift."""
    companion = [p for p in trajectory.particles if p.startswith(COMPANION)]
    if not companion:
        return [], []
    axes, up = trajectory.axes, scene["up"]
    side = [1.0, 0.0, 0.0][:len(axes)] if abs(up[0]) < 0.9 else [0.0, 1.0, 0.0][:len(axes)]
    own = [p for p in trajectory.particles if not p.startswith(COMPANION)]
    across = [sum(s * trajectory.path(point, a)[row] for s, a in zip(side, axes))
              for point in own + trajectory.fixed_points for row in range(len(trajectory.t))]
    width = max(across) - min(across)
    shift = [s * max(1.3 * width, 0.5) for s in side]
    columns = trajectory.columns
    for point in trajectory.fixed_points:
        for a in axes:
            columns[f"{COMPANION}{point}_{a}"] = list(columns[f"{point}_{a}"])
    for point in companion + [COMPANION + p for p in trajectory.fixed_points]:
        for offset, a in zip(shift, axes):
            columns[f"{point}_{a}"] = [value + offset for value in columns[f"{point}_{a}"]]
    return companion + [COMPANION + p for p in trajectory.fixed_points], shift


def page_data(csv_path: str, scene: dict) -> dict:
    """Everything the page's script reads: the scene and the trajectory's arrays."""
    trajectory = read_trajectory(csv_path)
    columns, dim = trajectory.columns, scene["dim"]
    _check_matches(trajectory, scene, csv_path)
    coordinates = [name[2:] for name in columns if name.startswith("q_")]
    companion, shift = _side_by_side(trajectory, scene)
    points = [*(p for p in trajectory.particles if not p.startswith(COMPANION)),
              *trajectory.fixed_points, *companion]
    rows, stride = kept_rows(len(trajectory.t), 2 + len(coordinates) + dim * len(points))
    error = energy_error(trajectory.energy, scene.get("conserves_energy", True),
                         trajectory.work)
    positions = [columns[f"{point}_{axis}"][row]
                 for row in rows for point in points for axis in "xyz"[:dim]]
    return {
        "scene": scene,
        "source": os.path.basename(csv_path),
        "rows": len(trajectory.t), "stride": stride, "frames": len(rows),
        "coordinates": coordinates,
        "points": points,            # particles, "fixed:<name>", then the companion's
        "companion": COMPANION if companion else None,
        "companion_shift": shift,
        "energy": {"label": error.label, "name": error.name, "relative": error.relative,
                   "worst": error.worst, "summary": error.summary()},
        "arrays": {
            "t": encoded([trajectory.t[row] for row in rows], "d"),
            "energy_error": encoded(_worst_in_buckets(error.values, rows), "f"),
            # a dissipative model's W(t), scaled alike, drawn with it: E - E0 should follow it
            **({"work": encoded([error.work[row] for row in rows], "f")}
               if error.work is not None else {}),
            "q": encoded([columns["q_" + c][row] for row in rows for c in coordinates], "f"),
            "positions": encoded(positions, "f"),   # frames x points x dim
        },
    }


def _check_matches(trajectory, scene: dict, csv_path: str) -> None:
    """A ToolError unless the CSV has the scene's dimension and a path for each of its
    particles and fixed points (a trajectory of another model has not)."""
    if len(trajectory.axes) != scene["dim"]:
        raise ToolError(f"{csv_path}: positions in {len(trajectory.axes)}D, but {scene['name']} "
                        f"is a {scene['dim']}D model; is it a trajectory of another model?")
    names = [p["name"] for p in scene["particles"]] + \
        [FIXED_PREFIX + p for p in scene["fixed_points"]]
    known = set(trajectory.particles) | set(trajectory.fixed_points)
    for name in names:
        if name not in known:
            raise ToolError(f"{csv_path}: no position columns of {name!r} of {scene['name']}; "
                            "is it a trajectory of another model?")


def _data_url(source: str) -> str:
    return "data:text/javascript;base64," + base64.b64encode(source.encode()).decode("ascii")


def _script_safe(text: str) -> str:
    """Text that cannot end the <script> element it sits in."""
    return text.replace("</", "<\\/")


def page_html(data: dict, title: str) -> str:
    """The page that plays `data` (page_data's layout)."""
    library = three_js.sources()
    with open(os.path.join(HERE, "page.html"), encoding="utf-8") as handle:
        template = string.Template(handle.read())
    with open(os.path.join(HERE, "viewer.js"), encoding="utf-8") as handle:
        viewer = handle.read()
    imports = {"three": _data_url(library["three"]),
               "three/addons/controls/OrbitControls.js": _data_url(library["orbit_controls"])}
    return template.substitute(
        title=title.replace("&", "&amp;").replace("<", "&lt;"),
        three_version=three_js.VERSION,
        import_map=json.dumps({"imports": imports}),
        data=_script_safe(json.dumps(data, separators=(",", ":"))),
        viewer=_script_safe(viewer))


def write_page(csv_path: str, scene: dict, html_path: str, title: str) -> None:
    """Writes the page of a trajectory CSV, atomically: a reader never sees half of it."""
    write_data_page(page_data(csv_path, scene), html_path, title)


def write_data_page(data: dict, html_path: str, title: str) -> None:
    """Writes the page that plays `data`, atomically."""
    text = page_html(data, title)
    folder = os.path.dirname(os.path.abspath(html_path))
    descriptor, partial = tempfile.mkstemp(dir=folder, suffix=".partial")
    try:
        with os.fdopen(descriptor, "w", encoding="utf-8") as handle:
            handle.write(text)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(partial, 0o666 & ~umask)  # as open() would have made it, not mkstemp's 0600
        os.replace(partial, html_path)
    except BaseException:
        os.unlink(partial)
        raise


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("csv", help="a trajectory CSV that gencoord simulate wrote")
    parser.add_argument("scene", help="the model's <name>.scene.json, beside its header")
    parser.add_argument("html", help="the page to write")
    args = parser.parse_args(argv)
    try:
        with open(args.scene, encoding="utf-8") as handle:
            scene = json.load(handle)
        write_page(args.csv, scene, args.html, scene.get("name", "model"))
    except (ToolError, OSError, ValueError, KeyError) as error:
        print(f"view: error: {error}", file=sys.stderr)
        return 1
    print(args.html)
    return 0


if __name__ == "__main__":
    sys.exit(main())
