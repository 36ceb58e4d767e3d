#!/usr/bin/env bash
# Redraws docs/real_*.png: the automatic skeleton reconstruction of each real leaf-off cloud in
# ../shared/data/real (grey: the cloud; brown: the mesh), prints how well each model explains its
# cloud (reconstruct --report: points within ±1/2/5 cm, missed, volume, length, trunk diameter)
# and the same for rtwig's published SimpleForest cylinder model (fit-report), and the rtwig
# comparison with that model (wood volume Σπr²L, trunk-base radius, branch length).
# Usage: scripts/real_pictures.sh [BUILD_DIR]   (default build)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
bin="$here/${1:-build}/treesketch"
real="$here/../shared/data/real"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
draw() {  # name cloud
  "$bin" reconstruct "$real/$2" --auto --up z --cylinders "$tmp/$1.csv" --report "$tmp/$1.json" -o "$tmp/$1.ply"
  "$bin" render --cloud "$real/$2" --mesh "$tmp/$1.ply" --color-by none --view front --up z -o "$here/docs/real_$1.png"
}
draw rtwig rtwig_cloud.txt
draw adtree7 adtree_tree7.xyz
draw archi_tree2 archi_Tree_2_point_cloud.las
"$bin" fit-report "$real/rtwig_cloud.txt" "$real/rtwig_QSM_simpleforest.csv"
python3 - "$tmp/rtwig.csv" "$real/rtwig_QSM_simpleforest.csv" <<'PY'
import csv, math, sys
def table(path):
    with open(path) as f:
        rows = [{k.strip(): v for k, v in r.items()} for r in csv.DictReader(f)]
    vol = sum(math.pi * float(r["radius"]) ** 2 * float(r["length"]) for r in rows)
    return vol, float(rows[0]["radius"]), sum(float(r["length"]) for r in rows)
ours, qsm = table(sys.argv[1]), table(sys.argv[2])
print("rtwig            treesketch   SimpleForest QSM")
print("volume m^3       %10.4f   %10.4f  (%+.0f %%)" % (ours[0], qsm[0], 100 * (ours[0] / qsm[0] - 1)))
print("base radius m    %10.4f   %10.4f  (%+.0f %%)" % (ours[1], qsm[1], 100 * (ours[1] / qsm[1] - 1)))
print("branch length m  %10.1f   %10.1f" % (ours[2], qsm[2]))
PY
