#!/usr/bin/env python3
"""The automatic model on every tree cloud in ../shared/data/real, beside TreeQSM's model of the
same cloud: how well each model explains its cloud, its volume, DBH and height, and a picture.

Usage: scripts/real_scans.py [--build build] [--out docs/evaluation/real] [--only NAME ...]
                             [--extra DIR] [--extra-leaf-on DIR] [--extra-only]

The clouds in leaf are modelled with `--leaf-on --wood-only` (the points the wood/leaf
classification calls wood), the way to their wood's volume; their share within ±2 cm counts the
leaves too, so it is low.

Writes OUT/table.md (the Markdown table, tuning and held-out clouds apart), OUT/results.json and
OUT/<name>.png; prints the table. The clouds marked "tuning" are the ones the automatic model's
rules were developed on; the others are reported apart and never used to choose a setting.
TreeQSM's figures are those of ../shared/data/real/treeqsm (TreeQSM 2.4.1, quick-guide settings,
seed 1), measured against the cloud by the same fit-report as treesketch's own model.

--extra DIR adds every cloud file of DIR (leaf-off, Z up, metres) as a third group, "Other clouds"
(--extra-leaf-on DIR: clouds in leaf, modelled as those above are):
clouds of your own, or others' public ones, that no rule was chosen on. A TreeQSM model of a cloud
there is read from DIR/<stem>_cyl.txt and DIR/<stem>_treedata.txt (as `../shared/peers/treeqsm/
run.sh CLOUD DIR/<stem>` writes them); whether it is credible is measured, not given: at least
70 % of the points within ±5 cm of it and at most 2 % deeper than 2 cm inside.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REAL = os.path.join(HERE, "..", "shared", "data", "real")
CLOUD_EXTENSIONS = (".xyz", ".txt", ".las", ".laz", ".ply", ".asc", ".pts", ".csv")

# name, file, leaf-on, tuning, TreeQSM file stem (None: no model), TreeQSM credible
CLOUDS = [
    ("rtwig", "rtwig_cloud.txt", False, True, "rtwig_cloud", True),
    ("adtree_tree7", "adtree_tree7.xyz", False, True, "adtree_tree7", True),
    ("archi_tree2", "archi_Tree_2_point_cloud.las", False, True, "archi_Tree_2_point_cloud", True),
    ("voxr_t0", "voxr_Tree_t0.asc", False, True, "voxr_Tree_t0", True),
    ("rtls_leafon", "rtls_pc_tree.txt", True, True, "rtls_pc_tree", False),
    ("adtree_tree1", "adtree_tree1.xyz", False, False, "adtree_tree1", True),
    ("adtree_lille11", "adtree_Lille_11.xyz", False, False, "adtree_Lille_11", False),
    ("voxr_t1", "voxr_Tree_t1.asc", False, False, "voxr_Tree_t1", True),
    ("plantscan3d_branch", "plantscan3d_A3B4.asc", False, False, "plantscan3d_A3B4", True),
    ("ahn_airborne", "pctm_ahn_filtered_tree_121913_487434.las", False, False,
     "pctm_ahn_filtered_tree_121913_487434", False),
    ("itsme_tree1", "itsme_tree_1_pc.txt", True, False, "itsme_tree_1_pc", True),
    ("palm", "pytlidar_tree_1.las", True, False, "pytlidar_tree_1", False),
    ("spruce", "treels_spruce_decoded.xyz", True, False, "treels_spruce_decoded", False),
]


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


def treeqsm_volume(stem, folder):
    """TreeQSM's total volume (m^3) from its treedata text (litres) in `folder`, or None."""
    path = os.path.join(folder, stem + "_treedata.txt")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        for line in f:
            parts = line.replace("\t", " ").split()
            if parts and parts[0].lower().startswith("totalvolume"):
                return float(parts[-1]) / 1000.0
    return None


def fit_report(binary, cloud, table, tmp):
    out = os.path.join(tmp, "fit.json")
    rc, text = run([binary, "fit-report", cloud, table, "--up", "z", "--json", out])
    if rc != 0:
        return None
    with open(out) as f:
        return json.load(f)


def pct(x):
    return "—" if x is None or (isinstance(x, float) and math.isnan(x)) else "%.1f" % (100.0 * x)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", default=os.path.join("docs", "evaluation", "real"))
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--no-pictures", action="store_true")
    ap.add_argument("--extra", help="folder of more leaf-off clouds (Z up, metres), reported apart")
    ap.add_argument("--extra-leaf-on", help="folder of more clouds in leaf (Z up, metres), reported apart")
    ap.add_argument("--extra-only", action="store_true", help="with --extra or --extra-leaf-on: only those clouds")
    a = ap.parse_args()
    binary = os.path.join(HERE, a.build, "treesketch")
    out_dir = os.path.join(HERE, a.out)
    os.makedirs(out_dir, exist_ok=True)
    # name, cloud path, leaf-on, group (True tuning, False held-out, None other), TreeQSM stem,
    # TreeQSM folder, credible (None: measured)
    clouds = []
    if not a.extra_only:
        if not os.path.isdir(REAL):
            sys.exit("real_scans: ../shared/data/real not found beside the repository")
        clouds += [(n, os.path.join(REAL, f), leaf, tune, stem, os.path.join(REAL, "treeqsm"), cred)
                   for n, f, leaf, tune, stem, cred in CLOUDS]
    for folder, leaf_on in ((a.extra, False), (a.extra_leaf_on, True)):
        if not folder:
            continue
        if not os.path.isdir(folder):
            sys.exit("real_scans: %s is not a folder" % folder)
        for f in sorted(os.listdir(folder)):
            stem, ext = os.path.splitext(f)
            if ext.lower() in CLOUD_EXTENSIONS and not stem.endswith(("_cyl", "_treedata")):
                clouds.append((stem, os.path.join(folder, f), leaf_on, None, stem, folder, None))
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, cloud, leaf_on, tuning, qsm_stem, qsm_dir, credible in clouds:
            if a.only and name not in a.only:
                continue
            file = os.path.basename(cloud)
            if file.endswith(".asc") and run([binary, "info", cloud])[0] != 0:
                # A reader without the .asc variant: the same numbers, its header line dropped.
                plain = os.path.join(tmp, name + ".xyz")
                with open(cloud) as src, open(plain, "w") as dst:
                    dst.writelines(l for l in src if l.strip() and not l.lstrip().startswith('"'))
                cloud = plain
            mesh, csv, report = (os.path.join(tmp, name + e) for e in (".ply", ".csv", ".json"))
            cmd = [binary, "reconstruct", cloud, "--auto", "--up", "z", "-o", mesh, "--cylinders", csv,
                   "--report", report] + (["--leaf-on", "--wood-only"] if leaf_on else [])
            rc, text = run(cmd)
            r = {"name": name, "file": file, "leafOn": leaf_on, "tuning": tuning, "rc": rc}
            if rc == 0:
                with open(report) as f:
                    rep = json.load(f)
                fit, met = rep["model"]["fit"], rep["metrics"]
                r.update(within2=fit["within2cm"], inside2=fit["insideDeeper2cm"], missed5=fit["outsideFarther5cm"],
                         volume=met["volumeM3"], dbh=met["dbhModelM"], height=met["heightM"],
                         measuredShare=rep["model"].get("measuredVolumeShare"),
                         volumeRange=rep["model"].get("volumeRangeM3"), verdict=rep.get("verdict"))
                dbh = r["dbh"] if r["dbh"] is not None else float("nan")
                h = r["height"] if r["height"] is not None else float("nan")
                base = math.pi / 4 * dbh * dbh * h
                r["formFactor"] = r["volume"] / base if base > 0 else None
                if not a.no_pictures:
                    run([binary, "render", "--cloud", cloud, "--mesh", mesh, "--color-by", "none", "--view", "front",
                         "--up", "z", "--size", "600x600", "-o", os.path.join(out_dir, name + ".png")])
            else:
                r["error"] = text.strip().splitlines()[-1] if text.strip() else "exit %d" % rc
                r["error"] = r["error"].replace(cloud, file)  # no machine paths in the table
            qv = treeqsm_volume(qsm_stem, qsm_dir) if qsm_stem else None
            r["treeqsmVolume"] = qv
            r["treeqsmCredible"] = credible
            qcyl = os.path.join(qsm_dir, (qsm_stem or "") + "_cyl.txt")
            if qsm_stem and os.path.exists(qcyl):
                q = fit_report(binary, cloud, qcyl, tmp)
                if q:
                    r["treeqsmWithin2"] = q["fit"]["within2cm"]
                    r["treeqsmInside2"] = q["fit"]["insideDeeper2cm"]
                    if credible is None:
                        r["treeqsmCredible"] = q["fit"]["within5cm"] >= 0.7 and q["fit"]["insideDeeper2cm"] <= 0.02
            if rc == 0 and qv:
                r["volumeRatio"] = r["volume"] / qv
            results.append(r)
            print("%-20s rc %d %s" % (name, rc, r.get("error", "")), file=sys.stderr)
    with open(os.path.join(out_dir, "results.json"), "w") as f:
        json.dump(results, f, indent=2)
    lines = []
    for title, tuning in (("Tuning clouds", True), ("Held-out clouds", False), ("Other clouds", None)):
        if not any(r["tuning"] is tuning for r in results):
            continue
        lines += ["", "### " + title, "",
                  "| cloud | leaf | within ±2 cm % (TreeQSM) | > 2 cm inside % (TreeQSM) | missed > 5 cm % | volume m³ "
                  "| × TreeQSM (credible?) | measured share % | DBH cm | height m | form factor | verdict |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in results:
            if r["tuning"] is not tuning:
                continue
            leaf = "on (wood only)" if r["leafOn"] else "off"
            if r["rc"] != 0:
                lines.append("| %s | %s | failed: %s | | | | | | | | | |" % (r["name"], leaf, r["error"]))
                continue
            ratio = "%.2f (%s)" % (r["volumeRatio"], "yes" if r["treeqsmCredible"] else "no") \
                if r.get("volumeRatio") else "—"
            ff = "%.2f" % r["formFactor"] if r.get("formFactor") else "—"
            verdict = (r.get("verdict") or {}).get("level", "—")
            lines.append("| %s | %s | %s (%s) | %s (%s) | %s | %.4f | %s | %s | %s | %s | %s | %s |" % (
                r["name"], leaf, pct(r["within2"]), pct(r.get("treeqsmWithin2")), pct(r["inside2"]),
                pct(r.get("treeqsmInside2")), pct(r["missed5"]), r["volume"], ratio, pct(r.get("measuredShare")),
                "%.1f" % (100 * r["dbh"]) if r["dbh"] is not None else "—",
                "%.2f" % r["height"] if r["height"] is not None else "—", ff, verdict))
    ok = [r for r in results if r["rc"] == 0]
    if ok:
        worst = max(ok, key=lambda r: r["inside2"])
        lines += ["", "Worst share deeper than 2 cm inside: %s %% (%s)." % (pct(worst["inside2"]), worst["name"])]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out_dir, "table.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
