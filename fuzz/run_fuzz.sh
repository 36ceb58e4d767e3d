#!/usr/bin/env bash
# Runs each libFuzzer harness of a TREESKETCH_FUZZ build one after the other (one process each, so
# a shared machine keeps a core free) and prints a summary line per harness.
# Usage: fuzz/run_fuzz.sh BUILD_DIR SECONDS RUNS [HARNESS...]
#   SECONDS: time budget per harness (libFuzzer -max_total_time; 0 = none)
#   RUNS:    run budget per harness (libFuzzer -runs; -1 = none); the first budget reached stops it
#   HARNESS: names as in fuzz/<name>_fuzz.cpp (default: all)
# The summary lines are also appended to BUILD_DIR/fuzz-summary.txt under a line naming the
# invocation. Each harness's working corpus is BUILD_DIR/fuzz-corpus/<name> (seeded from fuzz/corpus/<name> and
# fuzz/regressions/<name>, growing across runs); a failing input is written to
# BUILD_DIR/fuzz-artifacts/<name>/ and the script exits non-zero after the remaining harnesses.
set -uo pipefail
build=$1 seconds=$2 runs=$3
shift 3
src=$(cd "$(dirname "$0")" && pwd)
if (($# == 0)); then
  set -- $(cd "$src" && ls *_fuzz.cpp | sed 's/_fuzz\.cpp$//')
fi
# file_sniff writes each input to a temporary file: keep those in memory when the machine can.
if [[ -z "${TMPDIR:-}" && -d /dev/shm && -w /dev/shm ]]; then export TMPDIR=/dev/shm; fi
summary="$build/fuzz-summary.txt"
echo "# $(date -u '+%Y-%m-%d %H:%M UTC') run_fuzz.sh $build $seconds $runs $*" >>"$summary"
failed=0
for name in "$@"; do
  exe="$build/fuzz/fuzz_$name"
  corpus="$build/fuzz-corpus/$name" artifacts="$build/fuzz-artifacts/$name"
  mkdir -p "$corpus" "$artifacts"
  log="$build/fuzz-$name.log"
  # -timeout: an input running over 10 s is a hang; -malloc_limit_mb: inputs are at most 4 KiB, so
  # no single allocation may approach 256 MB (declared counts must not allocate).
  "$exe" -max_total_time="$seconds" -runs="$runs" -timeout=10 -malloc_limit_mb=256 -max_len=4096 \
    -print_final_stats=1 -artifact_prefix="$artifacts/" "$corpus" "$src/corpus/$name" \
    $([[ -d "$src/regressions/$name" ]] && echo "$src/regressions/$name") >"$log" 2>&1
  rc=$?
  done_runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
  secs=$(grep -o 'Done [0-9]* runs in [0-9]* second' "$log" | grep -o 'in [0-9]*' | grep -o '[0-9]*' | tail -1)
  eps=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1)
  line="$name: runs=${done_runs:-?} seconds=${secs:-?} exec/s=${eps:-?} ${cov:-} exit=$rc corpus=$(ls "$corpus" | wc -l)"
  if ((rc != 0)); then
    failed=1
    line="$line FAILED (see $log, input in $artifacts/)"
  fi
  echo "$line" | tee -a "$summary"
done
exit $failed
