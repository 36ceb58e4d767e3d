#!/bin/bash
# `make test-slurm`: runs a plot as a Slurm job array on a real single-node cluster started here
# from Debian's packages, then checks every output and the summary. Installs slurm-wlm and munge
# when missing (apt-get, as root), starts munged (unless one runs), slurmctld and slurmd with a
# private configuration in a temporary folder (ports 16817/16818), and stops everything it
# started on exit. Not part of `make test` (it needs root and takes about a minute).
# Trees: the three real scans of ../shared/data/real and a truncated LAS (which must fail).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${TREESKETCH:-$here/build/treesketch}
real=$here/../shared/data/real
[ -x "$bin" ] || { echo "test-slurm: build first ($bin missing)" >&2; exit 1; }
[ -d "$real" ] || { echo "test-slurm: $real missing" >&2; exit 1; }

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends slurm-wlm munge >/dev/null
fi

work=$(mktemp -d /tmp/treesketch-slurm.XXXXXX)
started_munge=""
cleanup() {
  for d in slurmd slurmctld; do
    [ -f "$work/$d.pid" ] && kill "$(cat "$work/$d.pid")" 2>/dev/null || true
  done
  sleep 1
  if [ -n "$started_munge" ] && [ -f "$work/munged.pid" ]; then kill "$(cat "$work/munged.pid")" 2>/dev/null || true; fi
  rm -rf "$work"
}
trap cleanup EXIT

# munge: the authentication Slurm uses; a key of our own, our own socket.
mkdir -p "$work/munge"
chmod 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
socket=$work/munge/munge.socket
munged --force --key-file "$work/munge/munge.key" --socket "$socket" --pid-file "$work/munged.pid" \
  --log-file "$work/munged.log" --seed-file "$work/munge/seed"
started_munge=1

host=$(hostname -s)
node=$(slurmd -C | head -1 | sed -e "s/NodeName=[^ ]*/NodeName=$host/")
mkdir -p "$work/state" "$work/spool"
cat > "$work/slurm.conf" <<CONF
ClusterName=treesketchtest
SlurmctldHost=$host
SlurmctldPort=16817
SlurmdPort=16818
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
$node State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 30); do
  sinfo -h -o %T 2>/dev/null | grep -qE '^idle' && break
  sleep 1
done
sinfo -h -o %T | grep -qE '^idle' || { echo "test-slurm: the node did not come up" >&2; tail "$work"/*.log >&2; exit 1; }

# The plot: three real trees and a truncated LAS, in a manifest.
mkdir -p "$work/plot"
head -c 5000 "$real/archi_Tree_2_point_cloud.las" > "$work/plot/truncated.las"
printf '%s\n' "$real/adtree_tree7.xyz" "$real/archi_Tree_2_point_cloud.las" "$real/rtwig_cloud.txt" \
  "$work/plot/truncated.las" > "$work/trees.txt"
n=$(grep -cEv '^[[:space:]]*(#|$)' "$work/trees.txt")
out=$work/out
cd "$work"
TREESKETCH=$bin sbatch --wait --parsable --array=0-$((n - 1)) --export=ALL "$here/scripts/slurm/batch_array.sh" \
  "$work/trees.txt" "$out" >/dev/null || true  # --wait returns the highest task exit code: one tree fails
set +e
"$bin" batch "$work/trees.txt" --out "$out" --summarise
rc=$?
set -e
fail() { echo "test-slurm: FAILED: $*" >&2; exit 1; }
[ "$rc" -eq 6 ] || fail "summarise exit code $rc, expected 6 (one tree failed)"
for t in adtree_tree7 archi_Tree_2_point_cloud rtwig_cloud; do
  for f in mesh.ply cylinders.csv qsm.txt metrics.json report.json done.json; do
    [ -s "$out/$t/$f" ] || fail "$t/$f missing"
  done
done
[ -s "$out/truncated/failed.json" ] || fail "truncated/failed.json missing"
grep -q '"done": 3' "$out/summary.json" || fail "summary.json does not count 3 trees done"
[ "$(wc -l < "$out/summary.csv")" -eq 5 ] || fail "summary.csv should have a header and 4 rows"
ls slurm-*_*.out >/dev/null || fail "no Slurm task logs"
echo "test-slurm: passed ($n array tasks on a one-node Slurm cluster; 3 trees done, 1 failure recorded)"
