#!/usr/bin/env python3
"""What each setting of the automatic model buys: `reconstruct --auto` with one setting changed to
its neutral value (a rule switched off, a window of 1 or 0, a ratio at its no-op value), against
the defaults, on the leaf-off real clouds and on a few synthetic scans with their true volume.

Usage: scripts/ablation.py [--build build] [--out docs/evaluation/ablation] [--only LABEL ...]
                           [--list]

Measures per cloud: the share of points within ±2 cm of the model, the share deeper than 2 cm
inside it, and the volume (real clouds: over TreeQSM's model of the cloud; synthetic scans: over
the scanned branch mesh's exact volume, see scripts/synthetic_volume.py). Each configuration is
reported as its change from the defaults, with the tuning clouds (those the rules were developed
on) and the held-out ones apart. The first rows, "seed 2" and "seed 3", change only the circle
fits' random seed: they are the noise any other change must stand out of. The last table counts
the clouds on which a change left the model's figures exactly as the defaults' (a rule that never
acts there). Writes OUT/ablation.md (the table) and
OUT/ablation.json (every run); prints the table. One run at a time (the machine may be shared).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(HERE, "scripts"))
import real_scans  # noqa: E402  (the cloud list and TreeQSM's volumes)
import synthetic_volume  # noqa: E402  (the scans and the true volumes)

TREES = os.path.join(HERE, "..", "shared", "data", "trees")
SYNTHETIC_TREES = [("aspen_small_s914", True), ("pine_small_s3391", True), ("oak_small_s6120", False),
                   ("aspen_medium_s4409", False)]
SYNTHETIC_SCANS = ["sphere-295k", "tls-base"]

# label, --set assignments (or extra arguments): each a setting at its neutral value.
CONFIGS = [
    ("defaults", []),
    ("seed 2", ["--seed 2"]),
    ("seed 3", ["--seed 3"]),
    ("strays off", ["strays.enabled=off"]),
    ("sparse links off", ["skeleton.graph.sparseLinkNeighbours=0"]),
    ("bridge cone: all gaps free", ["skeleton.graph.freeGapVoxels=1000000"]),
    ("stem tracking off", ["skeleton.trackStem=off"]),
    ("fork split off", ["skeleton.splitMergedForks=off"]),
    ("spur rule off", ["skeleton.spurLengthRadii=0", "skeleton.spurLengthBins=0"]),
    ("twig-out rule off", ["skeleton.twigOutBins=0"]),
    ("end support rule off", ["skeleton.minEndSupportFraction=0"]),
    ("fork zone off", ["skeleton.forkZoneRadii=0"]),
    ("raw radius median off", ["skeleton.radiusMedianWindow=1"]),
    ("segment by radii only", ["skeleton.maxSegmentBins=1000000"]),
    ("fit growth off", ["fit.maxGrowthSteps=0"]),
    ("fit RMS floor 0", ["radii.rmsFloorVoxels=0"]),
    ("fit check slack 0", ["radii.slackVoxels=0"]),
    ("inlier band floor off", ["minInlierBandVoxels=0"]),
    ("fitted radius median off", ["radii.medianWindow=1"]),
    ("child-not-thicker off", ["radii.childNotThicker=off"]),
    ("allometry bound off", ["radii.allometryMaxRatio=0"]),
    ("surface bound off", ["radii.surfaceBound=off"]),
    ("axis smoothing off", ["axes.halfWindowNodes=0"]),
    ("completion off", ["completion.enabled=off"]),
    ("completion: one round", ["completion.maxRounds=1"]),
]


def config_args(assignments):
    """Command-line arguments: NAME=VALUE becomes --set NAME=VALUE; "--flag value" is passed as is."""
    args = []
    for s in assignments:
        args += s.split() if s.startswith("--") else ["--set", s]
    return args


def real_clouds(tmp, binary):
    """(name, path, tuning, reference volume m^3 or None) for every leaf-off tree of real_scans."""
    out = []
    for name, file, leaf_on, tuning, qsm_stem, _credible in real_scans.CLOUDS:
        if leaf_on:
            continue
        path = os.path.join(real_scans.REAL, file)
        if not os.path.exists(path):
            continue
        if file.endswith(".asc") and real_scans.run([binary, "info", path])[0] != 0:
            plain = os.path.join(tmp, name + ".xyz")
            with open(path) as src, open(plain, "w") as dst:
                dst.writelines(l for l in src if l.strip() and not l.lstrip().startswith('"'))
            path = plain
        out.append({"name": name, "path": path, "tuning": tuning, "kind": "real", "up": "z", "units": 1.0,
                    "reference": real_scans.treeqsm_volume(qsm_stem) if qsm_stem else None})
    return out


def synthetic_clouds(tmp, binary):
    """The scans of SYNTHETIC_TREES (Y up, 0.1 m a unit) with the scanned mesh's exact volume, m^3."""
    out = []
    for tree, tuning in SYNTHETIC_TREES:
        skeleton = os.path.join(TREES, tree + ".json")
        if not os.path.exists(skeleton):
            continue
        with open(skeleton) as f:
            _round, scanned = synthetic_volume.true_volumes(json.load(f))
        for scan in SYNTHETIC_SCANS:
            cloud = os.path.join(tmp, "%s_%s.ply" % (tree, scan))
            subprocess.run([binary, "scan", os.path.join(TREES, tree + ".branches.obj"), "-o", cloud] +
                           synthetic_volume.SCANS[scan], check=True, capture_output=True)
            out.append({"name": "%s/%s" % (tree, scan), "path": cloud, "tuning": tuning, "kind": "synthetic",
                        "up": "y", "units": 0.1, "reference": scanned * 0.1 ** 3})
    return out


def run_one(binary, cloud, args, tmp):
    report = os.path.join(tmp, "report.json")
    if os.path.exists(report):
        os.remove(report)
    cmd = [binary, "reconstruct", cloud["path"], "--auto", "--up", cloud["up"], "--units-metres",
           str(cloud["units"]), "-o", os.path.join(tmp, "model.ply"), "--report", report] + args
    rc, text = real_scans.run(cmd)
    if rc != 0:
        return {"rc": rc, "error": text.strip().splitlines()[-1] if text.strip() else ""}
    with open(report) as f:
        rep = json.load(f)
    fit = rep["model"]["fit"]
    vol = rep["metrics"]["volumeM3"]
    ref = cloud["reference"]
    return {"rc": 0, "within2": fit["within2cm"], "inside2": fit["insideDeeper2cm"], "volume": vol,
            "volumeRatio": vol / ref if ref else None, "nodes": rep.get("skeletonNodes")}


def change(base, run, key):
    if base.get("rc") != 0 or run.get("rc") != 0 or base.get(key) is None or run.get(key) is None:
        return None
    if key == "volume":
        return run[key] / base[key] - 1.0 if base[key] > 0 else None
    return run[key] - base[key]


def group_cell(clouds, results, label, key, scale):
    """Mean and largest change over a group of clouds, as 'mean (largest)'; failures counted."""
    d = [change(results["defaults"][c["name"]], results[label][c["name"]], key) for c in clouds]
    fails = sum(1 for c in clouds if results[label][c["name"]].get("rc") != 0)
    vals = [x for x in d if x is not None]
    if not vals:
        return "—"
    mean = sum(vals) / len(vals)
    big = max(vals, key=abs)
    cell = "%+.1f (%+.1f)" % (scale * mean, scale * big)
    return cell + (" %d fail" % fails if fails else "")


def table(clouds, results):
    groups = [("real tuning", [c for c in clouds if c["kind"] == "real" and c["tuning"]]),
              ("real held-out", [c for c in clouds if c["kind"] == "real" and not c["tuning"]]),
              ("synthetic tuning", [c for c in clouds if c["kind"] == "synthetic" and c["tuning"]]),
              ("synthetic held-out", [c for c in clouds if c["kind"] == "synthetic" and not c["tuning"]])]
    lines = []
    for key, what, scale in (("within2", "share within ±2 cm, points", 100),
                             ("inside2", "share deeper than 2 cm inside, points", 100),
                             ("volume", "volume, % of the defaults' model", 100)):
        lines += ["", "Change of the %s: mean over the group (largest):" % what, "",
                  "| setting changed | " + " | ".join("%s (%d)" % (g, len(cs)) for g, cs in groups) + " |",
                  "|---|" + "---:|" * len(groups)]
        for label, _ in CONFIGS[1:]:
            if label in results:
                lines.append("| %s | " % label + " | ".join(group_cell(cs, results, label, key, scale)
                                                             for _, cs in groups) + " |")
    same = ["", "Clouds on which the figures (both shares, volume, node count) equal the defaults' exactly:", "",
            "| setting changed | identical | of |", "|---|---:|---:|"]
    keys = ("rc", "within2", "inside2", "volume", "nodes")
    for label, _ in CONFIGS[1:]:
        if label in results:
            n = sum(1 for c in clouds if all(results[label][c["name"]].get(k) == results["defaults"][c["name"]].get(k)
                                             for k in keys))
            same.append("| %s | %d | %d |" % (label, n, len(clouds)))
    lines += same
    base = ["", "The defaults on each cloud (share within ±2 cm, deeper than 2 cm inside, volume over the reference):",
            "", "| cloud | half | within ±2 cm | inside > 2 cm | volume / reference |", "|---|---|---:|---:|---:|"]
    for c in clouds:
        r = results["defaults"][c["name"]]
        if r.get("rc") != 0:
            base.append("| %s | %s | exit %d | | |" % (c["name"], "tuning" if c["tuning"] else "held-out", r["rc"]))
            continue
        ratio = "—" if r["volumeRatio"] is None else "%.2f" % r["volumeRatio"]
        base.append("| %s | %s | %.1f %% | %.1f %% | %s |" % (c["name"], "tuning" if c["tuning"] else "held-out",
                                                             100 * r["within2"], 100 * r["inside2"], ratio))
    return "\n".join(base + lines) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", default=os.path.join("docs", "evaluation", "ablation"))
    ap.add_argument("--only", nargs="*", help="configuration labels to run (the defaults always run)")
    ap.add_argument("--list", action="store_true", help="print the configurations and exit")
    a = ap.parse_args()
    if a.list:
        for label, sets in CONFIGS:
            print("%-28s %s" % (label, " ".join(config_args(sets))))
        return
    binary = os.path.join(HERE, a.build, "treesketch")
    if not os.path.isdir(real_scans.REAL) and not os.path.isdir(TREES):
        sys.exit("ablation: ../shared/data not found beside the repository")
    out_dir = os.path.join(HERE, a.out)
    os.makedirs(out_dir, exist_ok=True)
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        clouds = real_clouds(tmp, binary) + synthetic_clouds(tmp, binary)
        for label, sets in CONFIGS:
            if a.only and label != "defaults" and label not in a.only:
                continue
            results[label] = {c["name"]: run_one(binary, c, config_args(sets), tmp) for c in clouds}
            print("ran %-28s" % label, file=sys.stderr, flush=True)
    with open(os.path.join(out_dir, "ablation.json"), "w") as f:
        json.dump({"clouds": [{k: c[k] for k in ("name", "tuning", "kind", "reference")} for c in clouds],
                   "configs": dict(CONFIGS), "results": results}, f, indent=1)
    text = table(clouds, results)
    with open(os.path.join(out_dir, "ablation.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
