#!/usr/bin/env bash
# Runs an evaluation sweep as N shards with GNU parallel, here or on other machines over ssh,
# then merges them: `conicloc evaluate --sweep SWEEP --shard I/N --out OUT/shards/I` for I = 1..N,
# and `conicloc evaluate --merge OUT/shards/* --out OUT` here once every shard succeeded.
# Usage: scripts/parallel-sweep.sh SWEEP OUT N [--sshlogin HOSTS] [-- EXTRA_EVALUATE_OPTIONS...]
#   SWEEP     quick, full, robustness or a sweep file.
#   HOSTS     GNU parallel's --sshlogin list (e.g. `4/node1,4/node2,:`); every host must see the
#             conicloc program, the sweep file and OUT at the same paths (a shared file system).
#   The conicloc program is $CONICLOC (default: build/tools/conicloc of this checkout). Shards run
#   $CONICLOC_JOBS at a time per host (default: parallel's, one per CPU core).
# A shard that stops resumes when the script is run again with the same OUT.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

if [ $# -lt 3 ] || ! [[ $3 =~ ^[1-9][0-9]*$ ]]; then
  sed -n '2,12p' "$0" >&2
  exit 2
fi
sweep=$1
out=$(realpath -m "$2")
shards=$3
shift 3
remote=()
if [ "${1:-}" = "--sshlogin" ]; then
  [ $# -ge 2 ] || { echo "parallel-sweep: --sshlogin needs HOSTS" >&2; exit 2; }
  remote=(--sshlogin "$2")
  shift 2
fi
[ "${1:-}" = "--" ] && shift
case "$sweep" in
  quick|full|robustness) ;;
  *) [ -f "$sweep" ] || { echo "parallel-sweep: no sweep file $sweep" >&2; exit 2; }
     sweep=$(realpath "$sweep") ;;
esac
conicloc=$(realpath "${CONICLOC:-$root/build/tools/conicloc}")
[ -x "$conicloc" ] || { echo "parallel-sweep: no conicloc program at $conicloc (set CONICLOC)" >&2; exit 2; }
jobs=()
[ -n "${CONICLOC_JOBS:-}" ] && jobs=(--jobs "$CONICLOC_JOBS")

mkdir -p "$out/shards" "$out/logs"
quoted_extra=""
for option in "$@"; do quoted_extra+=" $(printf '%q' "$option")"; done
# Every shard runs to its end (a failed run does not stop the others); the merge only when all
# succeeded.
seq 1 "$shards" | parallel --will-cite "${jobs[@]}" "${remote[@]}" --halt never \
  --joblog "$out/logs/parallel.joblog" \
  "$(printf '%q' "$conicloc") evaluate --sweep $(printf '%q' "$sweep") --shard {}/$shards \
--out $(printf '%q' "$out")/shards/{}$quoted_extra > $(printf '%q' "$out")/logs/shard-{}.log 2>&1" ||
  { echo "parallel-sweep: shards failed (see $out/logs/parallel.joblog and shard-*.log);" \
      "run again to resume them" >&2; exit 1; }
shard_dirs=()
for i in $(seq 1 "$shards"); do shard_dirs+=("$out/shards/$i"); done
"$conicloc" evaluate --merge "${shard_dirs[@]}" --out "$out" 2>&1 | tee "$out/logs/merge.log"
exit "${PIPESTATUS[0]}"
