#!/usr/bin/env python3
"""Reads a real tree cloud, models it with treesketch, prints its metrics and plots the stem taper.

    PYTHONPATH=build/python python3 examples/python/taper.py [CLOUD] [-o taper.png] [--leaf-on]

CLOUD defaults to ../shared/data/real/adtree_tree7.xyz beside the repository. Writes a PNG (the
Agg backend: no display needed).
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import treesketch  # noqa: E402

REPO = pathlib.Path(__file__).resolve().parents[2]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cloud", nargs="?", default=str(REPO.parent / "shared" / "data" / "real" / "adtree_tree7.xyz"))
    ap.add_argument("-o", "--output", default="taper.png", help="the picture (PNG)")
    ap.add_argument("--leaf-on", action="store_true", help="the tree was scanned in leaf")
    args = ap.parse_args()

    cloud = treesketch.read_cloud(args.cloud)
    model = treesketch.reconstruct(cloud, leaf_on=args.leaf_on)
    print(f"{args.cloud}: {len(cloud)} points, {len(model.cylinders['id'])} cylinders ({model.up_reason})")
    print(model.metrics_table(), end="")

    # The stem's pieces (branch order 0): the diameter at each piece's upper end, against its
    # height above the model's base; and the metrics' taper table (every metre).
    cyl = model.cylinders
    up = {"y": 1, "z": 2}[model.up]
    base = min(cyl["start"][:, up].min(), cyl["end"][:, up].min())
    stem = cyl["branch_order"] == 0
    order = np.argsort(cyl["end"][stem, up])
    stem_heights = cyl["end"][stem, up][order] - base
    stem_diameters = 2 * cyl["radius"][stem][order]
    heights, diameters = model.taper
    metrics = model.metrics()
    fig, ax = plt.subplots(figsize=(4, 6))
    ax.plot(stem_diameters * 100, stem_heights, "-", color="0.6", label="stem pieces")
    ax.plot(diameters * 100, heights, "o", label="taper table (every metre)")
    dbh = metrics["cloud"]["dbh"]
    if dbh["ok"]:
        ax.plot([dbh["diameterM"] * 100], [dbh["sliceHeightM"]], "rs", label="DBH: circle fit to the cloud")
    ax.set_xlabel("stem diameter (cm)")
    ax.set_ylabel("height above the base (m)")
    ax.set_xlim(left=0)
    ax.set_title(pathlib.Path(args.cloud).name)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.output, dpi=100)
    print(f"taper: {np.count_nonzero(np.isfinite(diameters))} heights -> {args.output}")


if __name__ == "__main__":
    main()
