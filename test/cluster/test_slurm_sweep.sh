#!/usr/bin/env bash
# The quick sweep as 4 shards on the Slurm cluster that answers here (scripts/start-slurm.sh
# starts one on this machine), through scripts/slurm-sweep.sh; the merged report must have the
# unsharded sweep's runs and accuracy figures. Skips (77) without Slurm.
# Usage: test_slurm_sweep.sh CONICLOC REFERENCE_DIR OUT_DIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
conicloc=$1
reference=$2
out=$3
if ! command -v sbatch >/dev/null; then
  echo "SKIP: no Slurm here (apt-get install slurm-wlm munge; scripts/start-slurm.sh)"
  exit 77
fi
if ! sinfo --noheader --responding --format=%t 2>/dev/null | grep -qE 'idle|mix|alloc'; then
  echo "SKIP: no Slurm cluster answers (start one with scripts/start-slurm.sh)"
  exit 77
fi
[ -s "$reference/runs.csv" ] || { echo "no reference sweep in $reference" >&2; exit 1; }

rm -rf "$out"
submitted=$(CONICLOC=$conicloc "$here/../../scripts/slurm-sweep.sh" quick "$out" 4)
echo "$submitted"
merge=$(echo "$submitted" | awk '/^merge job/ { print $3 }')
[ -n "$merge" ] || { echo "no merge job id" >&2; exit 1; }

# The merge job runs after the shards; wait until it has ended (ctest's timeout bounds this).
state=PENDING
while true; do
  state=$(scontrol show job "$merge" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2)
  case "$state" in
    COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY|PREEMPTED|BOOT_FAIL|DEADLINE) break ;;
    "") echo "the merge job $merge is gone before it was seen to end" >&2; break ;;
  esac
  sleep 2
done
echo "merge job $merge: $state"
if [ "$state" != COMPLETED ]; then
  tail -n 20 "$out"/logs/*.log >&2 || true
  exit 1
fi
for i in 1 2 3 4; do
  runs=$(($(wc -l < "$out/shards/$i/runs.csv") - 1))
  echo "shard $i/4: $runs runs"
  [ "$runs" -gt 0 ] || { echo "shard $i/4 made no runs" >&2; exit 1; }
done
"$here/compare_sweeps.sh" "$reference" "$out"
