#!/usr/bin/env bash
# Submits an evaluation sweep to Slurm: an array job of N shards, each `conicloc evaluate --sweep
# SWEEP --shard I/N --out OUT/shards/I`, and a merge job that runs once all of them succeeded
# (--dependency=afterok) and writes the whole sweep's report into OUT.
# Usage: scripts/slurm-sweep.sh SWEEP OUT N [-- EXTRA_EVALUATE_OPTIONS...]
#   SWEEP  quick, full, robustness or a sweep file; OUT and the sweep file must be on a file
#          system every node sees (the paths are made absolute).
#   The conicloc program is $CONICLOC (default: build/tools/conicloc of this checkout). Each shard
#   asks for $CONICLOC_CPUS CPUs (default 1; set `threads` in the sweep file to match). Other
#   sbatch settings come from sbatch's own environment variables (SBATCH_PARTITION,
#   SBATCH_ACCOUNT, SBATCH_TIMELIMIT, ...).
# Prints the array job's and the merge job's ids; the last line is `merge job ID`. A stopped
# shard resumes when submitted again with the same OUT: it skips the runs it has.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

if [ $# -lt 3 ] || ! [[ $3 =~ ^[1-9][0-9]*$ ]]; then
  sed -n '2,13p' "$0" >&2
  exit 2
fi
sweep=$1
out=$(realpath -m "$2")
shards=$3
shift 3
[ "${1:-}" = "--" ] && shift
case "$sweep" in
  quick|full|robustness) ;;
  *) [ -f "$sweep" ] || { echo "slurm-sweep: no sweep file $sweep" >&2; exit 2; }
     sweep=$(realpath "$sweep") ;;
esac
conicloc=$(realpath "${CONICLOC:-$root/build/tools/conicloc}")
[ -x "$conicloc" ] || { echo "slurm-sweep: no conicloc program at $conicloc (set CONICLOC)" >&2; exit 2; }
cpus=${CONICLOC_CPUS:-1}

mkdir -p "$out/shards" "$out/logs"
quoted_extra=""
for option in "$@"; do quoted_extra+=" $(printf '%q' "$option")"; done

array=$(sbatch --parsable --job-name=conicloc-sweep --array=1-"$shards" --cpus-per-task="$cpus" \
  --output="$out/logs/shard-%a.log" \
  --wrap="$(printf '%q' "$conicloc") evaluate --sweep $(printf '%q' "$sweep") \
--shard \${SLURM_ARRAY_TASK_ID}/$shards --out $(printf '%q' "$out")/shards/\${SLURM_ARRAY_TASK_ID}$quoted_extra")
array=${array%%;*}
echo "shards job $array (array 1-$shards)"

shard_dirs=""
for i in $(seq 1 "$shards"); do shard_dirs+=" $(printf '%q' "$out/shards/$i")"; done
merge=$(sbatch --parsable --job-name=conicloc-merge --dependency=afterok:"$array" \
  --kill-on-invalid-dep=yes --output="$out/logs/merge.log" \
  --wrap="$(printf '%q' "$conicloc") evaluate --merge$shard_dirs --out $(printf '%q' "$out")")
merge=${merge%%;*}
echo "merge job $merge"
