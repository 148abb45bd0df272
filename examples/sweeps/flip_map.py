"""The double pendulum's time-to-flip map, as a PNG, from the results of
examples/sweeps/double_pendulum_flip.toml (gencoord sweep). Run with Debian's python3, which
has h5py, NumPy and Matplotlib (scripts/setup.sh --sweep):

    /usr/bin/python3 examples/sweeps/flip_map.py out/double_pendulum_flip.h5 out/flip.png

Also checks the map against energy conservation: released at rest, neither rod can flip where
2 cos(theta1) + cos(theta2) > 1 (for equal lengths and masses), so no sample there may."""

import argparse
import sys

import h5py
import matplotlib
import numpy

matplotlib.use("Agg")
import matplotlib.colors  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def read(path: str):
    with h5py.File(path, "r") as results:
        columns = [c.decode() for c in results["samples"].attrs["columns"]]
        if columns != ["q.theta1", "q.theta2"] or "grid_points" not in results.attrs:
            sys.exit(f"{path}: not a grid over q.theta1, q.theta2 (it samples {columns})")
        done = results["chunk_done"][()]
        if not done.all():
            sys.exit(f"{path}: {int((done == 0).sum())} of {done.size} chunks are not done "
                     "yet; gencoord sweep ... --resume completes them")
        n1, n2 = (int(n) for n in results.attrs["grid_points"])
        samples = results["samples"][()].reshape(n1, n2, 2)
        flip = results["event_time"][()].reshape(n1, n2)
        status = results["status"][()].reshape(n1, n2)
        info = {key: results.attrs[key] for key in ("t_end", "dt", "integrator", "model")}
    return samples, flip, status, info


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("results", help="the sweep's HDF5 file")
    parser.add_argument("png", help="the picture to write")
    args = parser.parse_args()
    samples, flip, status, info = read(args.results)
    theta1, theta2 = samples[..., 0], samples[..., 1]
    forbidden = 2 * numpy.cos(theta1) + numpy.cos(theta2) > 1
    flipped = ~numpy.isnan(flip)
    print(f"{flip.size} samples, {int(flipped.sum())} flip by t = {info['t_end']:g} s "
          f"(median {numpy.nanmedian(flip):.3g} s), {int((status != 1).sum())} failed; "
          f"{int((flipped & forbidden).sum())} flip where energy forbids it")

    figure, axes = plt.subplots(figsize=(7.2, 6), dpi=110)
    colors = matplotlib.colormaps["magma"].copy()
    colors.set_bad("white")  # no flip before the cap
    extent = (theta1.min(), theta1.max(), theta2.min(), theta2.max())
    image = axes.imshow(flip.T, origin="lower", extent=extent, cmap=colors,
                        norm=matplotlib.colors.LogNorm(vmin=info["dt"], vmax=info["t_end"]),
                        interpolation="nearest")
    axes.contour(theta1, theta2, 2 * numpy.cos(theta1) + numpy.cos(theta2), levels=[1],
                 colors="tab:cyan", linewidths=0.8)
    axes.set_xlabel("theta1 (rad)")
    axes.set_ylabel("theta2 (rad)")
    n1, n2 = flip.shape
    model = info["model"].decode()
    integrator = info["integrator"].decode()
    axes.set_title(f"{model}: time to flip from rest, {n1} x {n2} samples\n"
                   f"{integrator}, dt = {info['dt']:g} s; white: no flip by "
                   f"{info['t_end']:g} s; cyan: energy forbids a flip inside", fontsize=10)
    figure.colorbar(image, ax=axes, label="time to flip (s)")
    figure.tight_layout()
    figure.savefig(args.png)
    print(args.png)


if __name__ == "__main__":
    main()
