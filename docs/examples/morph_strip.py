"""A morph strip with the overlap depth shaded (docs/python.md).

Every in-between immerse makes is the boundary of an immersed disk: a disk
laid on the plane that may lie over itself. The depth at a point is how many
layers of the disk cover it, the number of the frame's triangles that
contain it. This script draws a strip of frames, each shaded by its depth.

    python docs/examples/morph_strip.py [A B] [--frames N] [-o strip.png]

A and B are curve files (default: two of the repository's sample curves).
"""

import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import BoundaryNorm, ListedColormap  # noqa: E402
from matplotlib.path import Path  # noqa: E402

import immerse  # noqa: E402

CURVES = pathlib.Path(__file__).resolve().parents[2] / "curves"


def depth(frame, xs, ys):
    """Layers of the immersed disk over each grid point: the frame's triangles containing it."""
    grid = np.column_stack([g.ravel() for g in np.meshgrid(xs, ys)])
    count = np.zeros(len(grid), dtype=int)
    for tri in frame.points[frame.triangles.astype(np.intp)]:
        count += Path(tri).contains_points(grid)
    return count.reshape(len(ys), len(xs))


def draw(a, b, frames, output, resolution=220):
    tween = immerse.Tween(a, b)
    times = np.linspace(0.0, 1.0, frames)
    shown = [tween.frame(t) for t in times]
    lo = np.min([f.points.min(axis=0) for f in shown], axis=0)
    hi = np.max([f.points.max(axis=0) for f in shown], axis=0)
    pad = 0.04 * (hi - lo).max()
    xs = np.linspace(lo[0] - pad, hi[0] + pad, resolution)
    ys = np.linspace(lo[1] - pad, hi[1] + pad, resolution)
    depths = [depth(f, xs, ys) for f in shown]
    top = max(int(d.max()) for d in depths)
    colours = ListedColormap(["white"] + [plt.cm.viridis_r(0.15 + 0.8 * k / max(top, 1)) for k in range(1, top + 1)])
    norm = BoundaryNorm(np.arange(-0.5, top + 1.5), colours.N)
    fig, axes = plt.subplots(1, frames, figsize=(1.9 * frames, 2.6), squeeze=False)
    for ax, f, d in zip(axes[0], shown, depths):
        image = ax.imshow(d, origin="lower", extent=(xs[0], xs[-1], ys[0], ys[-1]), cmap=colours, norm=norm, interpolation="nearest")
        outline = np.vstack([f.points, f.points[:1]])
        ax.plot(outline[:, 0], outline[:, 1], color="black", linewidth=0.8)
        ax.set_title(f"t = {f.t:.2f}", fontsize=9)
        ax.set_aspect("equal")
        ax.axis("off")
    bar = fig.colorbar(image, ax=axes[0].tolist(), ticks=range(top + 1), fraction=0.02, pad=0.01)
    bar.set_label("overlap depth")
    fig.savefig(output, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return depths


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("a", nargs="?", default=str(CURVES / "spiral-strip-400deg-n30.json"))
    parser.add_argument("b", nargs="?", default=str(CURVES / "curl-strip-n10.json"))
    parser.add_argument("--frames", type=int, default=7)
    parser.add_argument("-o", "--output", default="morph-strip.png")
    args = parser.parse_args()
    depths = draw(args.a, args.b, args.frames, args.output)
    print(f"{args.output}: {args.frames} frames, deepest overlap {max(int(d.max()) for d in depths)} layers")


if __name__ == "__main__":
    main()
