#!/usr/bin/env bash
# Redraws the pictures of the desktop tool in docs/gui.md (docs/gui_*.png) under a virtual X server:
# - docs/gui_menu.png, gui_dialog.png, gui_classes.png, gui_intensity.png, gui_measure.png,
#   gui_help.png: the menu bar, the open dialog, colour by classification and by intensity with
#   their legends, the axis gizmo and scale bar, picking and measuring, the keys overlay
#   (apps/viewer/docs_features.json) on a cloud with file attributes made here: the demo tree's
#   branches and leaves scanned apart (treesketch scan), turned Z-up, with a synthetic ground disc,
#   written as a text cloud "X Y Z Intensity Classification" — classes 2 ground, 5 high vegetation
#   (the leaves), 64 (user defined: the wood); intensity simulated as a reflectance per class
#   (ground 0.25, leaves 0.35, wood 0.6) times 65535 with ±15 % noise. The attributes are made up
#   to show the feature; the geometry is the demo tree's.
# (docs/gui_sketch.png and gui_mesh.png come from apps/viewer/docs_screenshots.json, and
# docs/gui_stroke_drawn.png, gui_subtree.png, gui_distance.png from apps/viewer/docs_edits.json,
# and docs/gui_wood.png from apps/viewer/docs_wood.json (with --demo-rays 300000), all run by hand
# with `treesketch gui --script` on the demo tree, in docs/.)
# Usage: scripts/gui_screenshots.sh [BUILD_DIR]   (default build; needs xvfb-run and Mesa)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="$here/${1:-build}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
gui() { LIBGL_ALWAYS_SOFTWARE=1 XDG_CONFIG_HOME="$tmp/config" xvfb-run -a -s "-screen 0 1280x800x24" "$build/treesketch-gui" "$@"; }

cd "$here"
# The cloud with attributes.
"$build/treesketch" demo --out "$tmp/demo" > /dev/null
"$build/treesketch" scan "$tmp/demo/tree_branches.obj" -o "$tmp/wood.xyz" --up y --subdiv 6 --seed 3 > /dev/null
"$build/treesketch" scan "$tmp/demo/tree_leaves.obj" -o "$tmp/leaves.xyz" --up y --subdiv 6 --seed 4 > /dev/null
mkdir -p "$tmp/plot"
{
  echo "X Y Z Intensity Classification"
  # (x, y, z) Y-up -> (x, -z, y) Z-up
  awk 'BEGIN { srand(5) } { printf "%s %.6f %s %d 64\n", $1, -$3, $2, 65535 * 0.6 * (0.85 + 0.3 * rand()) }' "$tmp/wood.xyz"
  awk 'BEGIN { srand(6) } { printf "%s %.6f %s %d 5\n", $1, -$3, $2, 65535 * 0.35 * (0.85 + 0.3 * rand()) }' "$tmp/leaves.xyz"
  awk 'BEGIN { srand(7); for (i = 0; i < 6000; ++i) { r = 3.5 * sqrt(rand()); a = 6.2831853 * rand();
       printf "%.4f %.4f %.4f %d 2\n", r * cos(a), r * sin(a), 0.02 * rand() - 0.01, 65535 * 0.25 * (0.85 + 0.3 * rand()) } }'
} > "$tmp/plot/demo_plot.txt"
"$build/treesketch" info "$tmp/plot/demo_plot.txt" | head -3
cp "$tmp/demo/cloud.ply" "$tmp/plot/"
cp "$tmp/demo/sketch_user.json" "$tmp/plot/"
(cd "$tmp/plot" && gui demo_plot.txt --up z --sketch demo_plot.sketch.json \
  --script "$here/apps/viewer/docs_features.json")
for f in menu dialog classes intensity measure help; do mv "$tmp/plot/gui_$f.png" "$here/docs/gui_$f.png"; done
echo "wrote docs/gui_{menu,dialog,classes,intensity,measure,help}.png"
