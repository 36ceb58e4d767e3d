#!/bin/bash
# Crash recovery, as a person meets it: a session makes edits and is killed with SIGKILL mid-way;
# the restarted window offers the autosave back, a click made before answering does not overwrite
# it, and Restore brings the nodes back. Run by CTest (gui.crash_recovery) under xvfb-run:
#   crash_recovery.sh GUI CHECK TESTS_DIR
set -u
gui=$1 check=$2 dir=$3
save=crash_tree.autosave.sketch.json
run() { "$gui" --demo-rays 30000 --autosave "$save" --script "$dir/$1"; }
fail() { echo "crash_recovery: FAILED: $*" >&2; exit 1; }
rm -f "$save" crash_tree.autosave.kept-*.sketch.json

# 1. Four clicks, then the session idles; killed once its autosave holds them.
# (exec: the background job is the window itself, so SIGKILL reaches it and not a subshell)
(exec "$gui" --demo-rays 30000 --autosave "$save" --script "$dir/crash_edit.json") &
pid=$!
for _ in $(seq 1 900); do
  "$check" --sketch "$save" --nodes 4 >/dev/null 2>&1 && break
  kill -0 "$pid" 2>/dev/null || fail "the first session ended before it was killed"
  sleep 0.2
done
"$check" --sketch "$save" --nodes 4 || fail "the first session never autosaved its 4 nodes"
kill -9 "$pid"
wait "$pid"
status=$?
[ "$status" -eq 137 ] || fail "the first session was not killed by SIGKILL (status $status)"
echo "crash_recovery: killed the session (SIGKILL) with 4 nodes autosaved"

# 2. Restart: offered; a click before answering edits the view's sketch but not the autosave.
run crash_restart_click.json || fail "restart 1: the offer was not made (see the expectations above)"
"$check" --sketch "$save" --nodes 4 || fail "restart 1: the autosave was overwritten before the choice"

# 3. Restart: Restore brings the 4 nodes back (fitted), undoably.
run crash_restore.json || fail "restart 2: restore did not bring the nodes back"
"$check" --sketch "$save" --nodes 4 || fail "restart 2: the restored sketch was not autosaved"
echo "crash_recovery: passed"
