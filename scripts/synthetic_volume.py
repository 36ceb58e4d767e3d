#!/usr/bin/env python3
"""The automatic model's wood volume against the exact volume of the synthetic trees.

Usage: scripts/synthetic_volume.py [--build build] [--trees ../shared/data/trees] [--out DIR]

For every tree of the folder (ez-tree meshes with their exact skeleton JSON, Y up, 0.1 m per
unit), leaf-off: a sphere scan (the thesis's scanner, 294,912 rays) and a terrestrial scan
(4 stations, 0.2° steps, 5 mm noise) of the branch mesh, `reconstruct --auto`, and the model's
volume over the tree's: the sum of the frustums between consecutive sections of every branch of
the skeleton. Prints a Markdown table (tuning and held-out halves as the evaluation splits them)
with the mean absolute and the worst error; writes OUT/volume.md and OUT/volume.csv.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TUNING = {"ash_small_s2203", "aspen_medium_s101", "aspen_small_s914", "bush_2_s45590", "oak_medium_s35729",
          "pine_medium_s13977", "pine_small_s3391"}
SCANS = {
    "sphere-295k": ["--pattern", "sphere", "--subdiv", "7"],
    "tls-base": ["--pattern", "tls", "--up", "y", "--units-metres", "0.1", "--step", "0.2", "--noise", "0.005"],
}


def true_volume(skeleton_json):
    """Sum over branches of the frustums between consecutive sections, in model units³."""
    total = 0.0
    for branch in skeleton_json["skeleton"]["branches"]:
        sections = branch["sections"]
        for a, b in zip(sections, sections[1:]):
            length = math.dist(a["center"], b["center"])
            r0, r1 = a["radius"], b["radius"]
            total += math.pi * length * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0
    return total


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--trees", default=os.path.join(HERE, "..", "shared", "data", "trees"))
    ap.add_argument("--out", default=os.path.join("docs", "evaluation", "volume"))
    a = ap.parse_args()
    binary = os.path.join(HERE, a.build, "treesketch")
    out_dir = os.path.join(HERE, a.out)
    os.makedirs(out_dir, exist_ok=True)
    trees = sorted(f[:-5] for f in os.listdir(a.trees) if f.endswith(".json"))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in trees:
            with open(os.path.join(a.trees, name + ".json")) as f:
                truth = true_volume(json.load(f))
            mesh = os.path.join(a.trees, name + ".branches.obj")
            for scan, args in SCANS.items():
                cloud, metrics = os.path.join(tmp, "c.ply"), os.path.join(tmp, "m.json")
                subprocess.run([binary, "scan", mesh, "-o", cloud] + args, check=True, capture_output=True)
                p = subprocess.run([binary, "reconstruct", cloud, "--auto", "--up", "y", "-o",
                                    os.path.join(tmp, "m.ply"), "--metrics", metrics], capture_output=True, text=True)
                if p.returncode != 0:
                    rows.append({"tree": name, "scan": scan, "truth": truth, "model": None, "error": None})
                    continue
                with open(metrics) as f:
                    model = json.load(f)["volumeM3"]  # model units³ (no --units-metres given)
                rows.append({"tree": name, "scan": scan, "truth": truth, "model": model,
                             "error": model / truth - 1.0})
                print("%-22s %-12s truth %9.2f model %9.2f  %+6.1f %%" % (name, scan, truth, model,
                                                                           100 * (model / truth - 1)), file=sys.stderr)
    with open(os.path.join(out_dir, "volume.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["tree", "scan", "truth", "model", "error"])
        w.writeheader()
        w.writerows(rows)
    lines = ["| scan | half | trees | mean abs. volume error | worst (tree) |", "|---|---|---:|---:|---|"]
    for scan in SCANS:
        for half, names in (("tuning", TUNING), ("held-out", None)):
            sel = [r for r in rows if r["scan"] == scan and r["error"] is not None and
                   ((r["tree"] in TUNING) == (half == "tuning"))]
            if not sel:
                continue
            mean = sum(abs(r["error"]) for r in sel) / len(sel)
            worst = max(sel, key=lambda r: abs(r["error"]))
            lines.append("| %s | %s | %d | %.1f %% | %+.1f %% (%s) |" % (scan, half, len(sel), 100 * mean,
                                                                       100 * worst["error"], worst["tree"]))
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out_dir, "volume.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
