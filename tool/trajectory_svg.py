#!/usr/bin/env python3
"""Draws a trajectory CSV from `simulate` as an SVG: particle paths and energy against time.

    plot_trajectory.py out/double_pendulum.csv out/double_pendulum.svg

Standard library only. Paths are drawn in the two spatial axes along which the particles
move the most (the plane of motion for planar models).
"""
import csv
import sys

WIDTH, HEIGHT, MARGIN = 900, 420, 40
COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2"]


def read(path):
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    header, data = rows[0], [[float(x) for x in row] for row in rows[1:]]
    return header, list(zip(*data))


def polyline(xs, ys, bounds, rect, colour, equal_aspect):
    """An SVG polyline of (xs, ys) mapped from `bounds` (x0, x1, y0, y1) into `rect`."""
    (x0, x1, y0, y1), (left, top, w, h) = bounds, rect
    sx, sy = w / ((x1 - x0) or 1.0), h / ((y1 - y0) or 1.0)
    if equal_aspect:
        sx = sy = min(sx, sy)
    step = max(1, len(xs) // 2000)  # keep the file small
    points = " ".join(f"{left + (x - x0) * sx:.1f},{top + h - (y - y0) * sy:.1f}"
                      for x, y in list(zip(xs, ys))[::step])
    return f'<polyline fill="none" stroke="{colour}" stroke-width="1.2" points="{points}"/>'


def main(source, target):
    header, columns = read(source)
    column = dict(zip(header, columns))
    t, energy = column["t"], column["energy"]
    axes = [name for name in header if name.rsplit("_", 1)[-1] in ("x", "y", "z")
            and not name.startswith(("q_", "v_"))]
    particles = sorted({name.rsplit("_", 1)[0] for name in axes},
                       key=lambda p: header.index(p + "_x"))
    spread = {a: sum(max(column[f"{p}_{a}"]) - min(column[f"{p}_{a}"]) for p in particles)
              for a in "xyz" if f"{particles[0]}_{a}" in column}
    ax, ay = sorted(sorted(spread, key=lambda a: -spread[a])[:2])
    xs = [v for p in particles for v in column[f"{p}_{ax}"]] + [0.0]
    ys = [v for p in particles for v in column[f"{p}_{ay}"]] + [0.0]
    size = HEIGHT - 2 * MARGIN
    path_bounds = (min(xs), max(xs), min(ys), max(ys))
    path_rect = (MARGIN, MARGIN, size, size)
    de = [e - energy[0] for e in energy]
    energy_bounds = (t[0], t[-1], min(de), max(de) if max(de) > min(de) else min(de) + 1e-300)
    energy_rect = (size + 3 * MARGIN, MARGIN, WIDTH - size - 4 * MARGIN, size)
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" '
             f'font-family="sans-serif" font-size="13">',
             '<rect width="100%" height="100%" fill="white"/>',
             f'<text x="{MARGIN}" y="24">particle paths ({ax}, {ay}): {source}</text>',
             f'<text x="{size + 3 * MARGIN}" y="24">energy drift E(t) - E(0), '
             f'max |dE| = {max(abs(d) for d in de):.3e}</text>']
    for k, p in enumerate(particles):
        colour = COLOURS[k % len(COLOURS)]
        parts.append(polyline(column[f"{p}_{ax}"], column[f"{p}_{ay}"], path_bounds, path_rect,
                              colour, equal_aspect=True))
        parts.append(f'<text x="{MARGIN}" y="{HEIGHT - 12 - 16 * k}" fill="{colour}">{p}</text>')
    left, top, w, h = energy_rect
    parts.append(f'<rect x="{left}" y="{top}" width="{w}" height="{h}" fill="none" '
                 'stroke="#999"/>')
    parts.append(polyline(t, de, energy_bounds, energy_rect, "#333", equal_aspect=False))
    parts.append(f'<text x="{left}" y="{top + h + 18}">t = {t[0]:g} s</text>')
    parts.append(f'<text x="{left + w - 70}" y="{top + h + 18}">t = {t[-1]:g} s</text>')
    parts.append("</svg>")
    with open(target, "w") as handle:
        handle.write("\n".join(parts) + "\n")
    print(f"picture     {target}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
