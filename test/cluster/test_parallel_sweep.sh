#!/usr/bin/env bash
# The quick sweep as 4 shards with GNU parallel on this machine, through
# scripts/parallel-sweep.sh; the merged report must have the unsharded sweep's runs and accuracy
# figures. Skips (77) without GNU parallel.
# Usage: test_parallel_sweep.sh CONICLOC REFERENCE_DIR OUT_DIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
conicloc=$1
reference=$2
out=$3
if ! command -v parallel >/dev/null; then
  echo "SKIP: no GNU parallel here (apt-get install parallel)"
  exit 77
fi
[ -s "$reference/runs.csv" ] || { echo "no reference sweep in $reference" >&2; exit 1; }

rm -rf "$out"
CONICLOC=$conicloc "$here/../../scripts/parallel-sweep.sh" quick "$out" 4
for i in 1 2 3 4; do
  runs=$(($(wc -l < "$out/shards/$i/runs.csv") - 1))
  echo "shard $i/4: $runs runs"
  [ "$runs" -gt 0 ] || { echo "shard $i/4 made no runs" >&2; exit 1; }
done
"$here/compare_sweeps.sh" "$reference" "$out"
