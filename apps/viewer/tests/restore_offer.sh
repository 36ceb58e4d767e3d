#!/bin/bash
# The restore offer meets the automatic model: a session on a cloud file leaves its autosave; the
# next session of the same cloud presses Auto skeleton on its first frame, while the offer of that
# autosave is open (the progress window then appears under the offer's modal dialog; Dear ImGui
# 1.86 aborted on an assertion there). Run by CTest (gui.restore_offer_job) under xvfb-run:
#   restore_offer.sh GUI CHECK TESTS_DIR
set -u
gui=$1 check=$2 dir=$3
fail() { echo "restore_offer: FAILED: $*" >&2; exit 1; }
rm -rf restore_offer_data && mkdir -p restore_offer_data || fail "cannot make restore_offer_data"
cp "$dir/data/small_trunk.txt" restore_offer_data/trunk.txt || fail "cannot copy the test cloud"
cloud=restore_offer_data/trunk.txt

"$gui" "$cloud" --script "$dir/restore_offer_edit.json" || fail "the first session failed"
"$check" --sketch "$cloud.autosave.sketch.json" --nodes 2 || fail "the first session left no autosave of its 2 nodes"
"$gui" "$cloud" --script "$dir/restore_offer_job.json" || fail "Auto skeleton under the restore offer (exit $?)"
echo "restore_offer: passed"
