#!/bin/bash
# One tree of a plot per Slurm array task: `treesketch batch MANIFEST --out OUT --index $SLURM_ARRAY_TASK_ID`.
#   n=$(grep -cEv '^[[:space:]]*(#|$)' trees.txt)
#   jid=$(sbatch --parsable --array=0-$((n - 1)) scripts/slurm/batch_array.sh trees.txt out/plot)
#   sbatch --dependency=afterany:$jid --wrap "treesketch batch trees.txt --out out/plot --summarise"
# Further arguments go to `treesketch batch` (--up, --leaf-on, --units-metres). TREESKETCH names the
# executable (default: treesketch on PATH). A task exits with the tree's exit code (0 done; 3 the
# cloud could not be read ...), which Slurm shows per task; the tree's failed.json says why.
#SBATCH --job-name=treesketch
#SBATCH --cpus-per-task=2
#SBATCH --output=slurm-%A_%a.out
set -eu
if [ $# -lt 2 ] || [ -z "${SLURM_ARRAY_TASK_ID:-}" ]; then
  echo "usage: sbatch --array=0-<trees - 1> $0 MANIFEST OUT [batch options]" >&2
  exit 2
fi
manifest=$1
out=$2
shift 2
exec "${TREESKETCH:-treesketch}" batch "$manifest" --out "$out" --index "$SLURM_ARRAY_TASK_ID" "$@"
