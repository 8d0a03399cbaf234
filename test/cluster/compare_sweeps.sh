#!/usr/bin/env bash
# Compares two sweep reports: the same runs.csv rows, column for column, except the measured
# times (time_per_scan_ms, time_p95_ms, realtime_factor, start_time_ms, search_time_mean_ms,
# search_time_max_ms, tracking_time_mean_ms), and the same report files.
# Usage: compare_sweeps.sh REFERENCE_DIR MERGED_DIR
set -euo pipefail
reference=$1
merged=$2

without_times() {
  awk -F, 'NR == 1 {
             for (i = 1; i <= NF; ++i)
               skip[i] = ($i == "time_per_scan_ms" || $i == "time_p95_ms" ||
                          $i == "realtime_factor" || $i == "start_time_ms" ||
                          $i ~ /^search_time_/ || $i == "tracking_time_mean_ms")
           }
           { line = ""
             for (i = 1; i <= NF; ++i) if (!skip[i]) line = line $i ","
             print line }' "$1"
}

status=0
for file in runs.csv summary.md robustness.md scale.md cost_against_size.svg pareto.svg; do
  [ -s "$merged/$file" ] || { echo "compare: $merged/$file is missing" >&2; status=1; }
done
rows=$(($(wc -l < "$reference/runs.csv") - 1))
[ "$rows" -gt 0 ] || { echo "compare: no runs in $reference/runs.csv" >&2; exit 1; }
if ! diff <(without_times "$reference/runs.csv") <(without_times "$merged/runs.csv") >&2; then
  echo "compare: the merged runs.csv differs from the unsharded one (< unsharded, > merged)" >&2
  status=1
fi
[ $status -eq 0 ] && echo "compare: $rows runs, the same rows and accuracy figures"
exit $status
