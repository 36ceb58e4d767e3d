#!/usr/bin/env bash
# Makes procedural test trees with the ez-tree generator (npm), in the layout of the developer
# trees (../shared/data/trees): OUT_DIR/<preset>_s<seed>.{branches.obj,leaves.obj,json}.
#   bash scripts/test_trees/make_trees.sh OUT_DIR "Oak Large:101" "Bush 1:202" ...
# The generator is installed into a scratch folder (npm; Node 18 or later), never into the
# repository. Its versions are the developer trees' own, so the same preset and seed give the same
# tree (checked: oak_small_s6120, bush_2_s45590 and pine_small_s3391 come out vertex for vertex).
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: $0 OUT_DIR \"Preset Name:seed\" ..." >&2
  exit 2
fi
command -v node >/dev/null && command -v npm >/dev/null || { echo "$0: needs node and npm (apt-get install nodejs npm)" >&2; exit 3; }
here="$(cd "$(dirname "$0")" && pwd)"
out="$1"; shift
scratch="${TREESKETCH_NPM_CACHE:-${TMPDIR:-/tmp}/treesketch-test-trees}"
mkdir -p "$scratch" "$out"
if [ ! -d "$scratch/node_modules/@dgreenheck/ez-tree" ]; then
  (cd "$scratch" && npm install --silent --no-audit --no-fund @dgreenheck/ez-tree@1.1.0 three@0.167.1 >&2)
fi
cp "$here/make_trees.mjs" "$scratch/make_trees.mjs"
node "$scratch/make_trees.mjs" "$out" "$@"
