#!/usr/bin/env bash
# Peak memory of `reconstruct --auto` per point: the demo tree scanned at about 0.5M, 1M and 2M
# points, each modelled under GNU time (maximum resident set size of the process), and — when
# heaptrack is installed — where the bytes of the largest run go at its peak (heap by allocating
# stage). Not part of `make test` or `make bench`; figures go to bench/README.md ("Memory of the
# automatic model") and docs/reliability.md. 20M points is extrapolated from these, never run here
# (bench/scale_20m.sh runs it where a machine can spare the memory).
#
# Usage: bench/memory_auto.sh [BUILD_DIR=build] [WORK_DIR=out/memory_auto]
set -euo pipefail
build=${1:-build}
work=${2:-out/memory_auto}
ts="$build/treesketch"
[[ -x "$ts" ]] || { echo "memory_auto: $ts not found (build first: make build)" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "memory_auto: needs GNU time (/usr/bin/time, Debian package 'time')" >&2; exit 2; }
mkdir -p "$work"
echo "# memory_auto: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# $("$ts" --version 2>/dev/null | head -1), git $(git rev-parse --short HEAD 2>/dev/null || echo '?')"

"$ts" demo --out "$work/demo" --subdiv 3 >/dev/null
echo "| rays | points | wall (s) | peak RSS (MB) | bytes a point |"
echo "|---:|---:|---:|---:|---:|"
largest=""
for rays in 1090000 2180000 4370000; do
  cloud="$work/cloud_$rays.ply"
  "$ts" scan "$work/demo/tree_branches.obj" --rays "$rays" -o "$cloud" >/dev/null
  points=$("$ts" info "$cloud" | awk '/^points:/ {print $2}')
  /usr/bin/time -f '%e %M' -o "$work/time_$rays.txt" "$ts" reconstruct "$cloud" --auto -o "$work/model_$rays.obj" \
    >"$work/reconstruct_$rays.out" 2>&1
  read -r wall kb <"$work/time_$rays.txt"
  awk -v r="$rays" -v p="$points" -v w="$wall" -v k="$kb" \
    'BEGIN {printf "| %d | %d | %.1f | %.0f | %.0f |\n", r, p, w, k / 1024, k * 1024 / p}'
  largest=$cloud
done

if command -v heaptrack >/dev/null && command -v heaptrack_print >/dev/null; then
  heaptrack -o "$work/heap" "$ts" reconstruct "$largest" --auto -o "$work/model_heap.obj" >/dev/null 2>&1
  heaptrack_print -f "$work/heap.zst" -p 0 -a 0 -T 0 -l 0 --flamegraph-cost-type peak -F "$work/peak_stacks.txt" \
    >/dev/null 2>&1
  echo
  echo "# heap at the peak of the largest run, by the innermost treesketch function that allocated it:"
  awk '{cost = $NF; $NF = ""; n = split($0, f, ";"); leaf = "?";
        for (i = n; i >= 1; --i) if (f[i] ~ /^treesketch::/) { leaf = f[i]; break }
        gsub(/\(anonymous namespace\)::/, "", leaf); sub(/\(.*/, "", leaf); sum[leaf] += cost; total += cost}
       END {for (k in sum) if (sum[k] > 0.01 * total) printf "%8.1f MB  %s\n", sum[k] / 1e6, k;
            printf "%8.1f MB  total\n", total / 1e6}' "$work/peak_stacks.txt" | sort -rn
fi
