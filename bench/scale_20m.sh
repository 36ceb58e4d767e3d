#!/usr/bin/env bash
# Scale benchmark: a ~20-million-point cloud through `info`, `reconstruct --auto` and
# `compare`, each timed with its peak memory (GNU time: wall clock and maximum resident set size of
# the child process). Not part of `make test`; figures go to bench/README.md.
#
# Usage: bench/scale_20m.sh [BUILD_DIR=build] [WORK_DIR=out/scale_20m] [RAYS=43700000]
# The cloud: the demo tree's branch mesh (`treesketch demo`, seed 1) scanned with the thesis's
# sphere pattern (`treesketch scan --rays RAYS`); 43.7M rays hit it ~46 % of the time, ~20M points.
# Needs about 2 GB of disk in WORK_DIR (binary PLY, 24 bytes a point) and ~2 GB of memory.
set -euo pipefail
build=${1:-build}
work=${2:-out/scale_20m}
rays=${3:-43700000}
ts="$build/treesketch"
[[ -x "$ts" ]] || { echo "scale_20m: $ts not found (build first: make build)" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "scale_20m: needs GNU time (/usr/bin/time, Debian package 'time')" >&2; exit 2; }
mkdir -p "$work"
echo "# scale_20m: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# $("$ts" --version 2>/dev/null | head -1), git $(git rev-parse --short HEAD 2>/dev/null || echo '?')"

# step NAME COMMAND...: runs the command under GNU time, prints "| NAME | wall s | peak MB |".
step() {
  local name=$1
  shift
  local log="$work/$name.time"
  /usr/bin/time -v -o "$log" "$@" >"$work/$name.out" 2>&1 || {
    echo "scale_20m: '$name' failed, see $work/$name.out" >&2
    exit 1
  }
  local wall rss
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i]; print s}' "$log")
  rss=$(awk -F': ' '/Maximum resident set size/ {printf "%.0f", $2 / 1024}' "$log")
  printf '| %-22s | %8.1f | %8s |\n' "$name" "$wall" "$rss"
}

"$ts" demo --out "$work/demo" --subdiv 3 >/dev/null
echo "| step                   | wall (s) | peak MB |"
echo "|------------------------|---------:|--------:|"
step scan "$ts" scan "$work/demo/tree_branches.obj" --rays "$rays" -o "$work/cloud.ply"
step info "$ts" info "$work/cloud.ply"
step "reconstruct --auto" "$ts" reconstruct --auto "$work/cloud.ply" -o "$work/model.obj"
step compare "$ts" compare "$work/model.obj" "$work/cloud.ply"
echo "# points: $(awk '/^points:/ {print $2}' "$work/info.out"); after: load average $(cut -d' ' -f1-3 /proc/loadavg)"
