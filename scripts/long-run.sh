#!/usr/bin/env bash
# The long run of issue #8: simulate MINUTES of a robot-mounted VLP-16 in the example building,
# localize the whole capture, and check that memory stays flat and updates do not slow down.
# Reports peak RSS at 5 minutes and at the end (from localize --details), time per scan over the
# first and last 5 minutes, and the pose error.
# Usage: scripts/long-run.sh [MINUTES (default 60)] [OUT_DIR (default out/long-run)] [localize options...]
# With REUSE_CAPTURE=1 an existing OUT_DIR/run.pcap (and its truth and odometry) is localized again.
set -euo pipefail
cd "$(dirname "$0")/.."
minutes=${1:-60}
out=${2:-out/long-run}
shift $(( $# > 2 ? 2 : $# ))
mkdir -p "$out"

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target conicloc --parallel "$(nproc)"
conicloc=build/tools/conicloc
seconds=$((minutes * 60))

if [ "${REUSE_CAPTURE:-0}" = 1 ] && [ -f "$out/run.pcap" ]; then
  echo "== reusing $out/run.pcap"
else
  echo "== simulate ${minutes} min"
  /usr/bin/time -f "simulate: %e s wall, peak RSS %M KiB" \
    $conicloc simulate --out "$out/run.pcap" --truth "$out/truth.tum" --odom "$out/odom.tum" \
      --duration "$seconds" --seed 7 2>&1 | tail -n 3
fi

init=$(awk '!/^#/ && NF == 8 {
  yaw = atan2(2 * ($8 * $7 + $5 * $6), 1 - 2 * ($6 * $6 + $7 * $7)) * 180 / 3.14159265358979;
  printf "%.3f,%.3f,%.3f,%.2f", $2, $3, $4, yaw; exit }' "$out/truth.tum")
echo "== localize ($(du -h "$out/run.pcap" | cut -f1) capture)"
/usr/bin/time -f "localize: %e s wall, peak RSS %M KiB" \
  $conicloc localize --pcap "$out/run.pcap" --odom "$out/odom.tum" --init "$init" \
  --out "$out/poses.tum" --details "$out/details.csv" "$@" 2>&1 | grep -v "^\s*scan" | tail -n 6

echo "== pose error"
$conicloc evaluate --truth "$out/truth.tum" --est "$out/poses.tum" --errors "$out/errors.csv" \
  2>&1 | tail -n 7

# details.csv: time_s is column 1, time_ms column 20, recovered 21, peak_rss_mib 22.
awk -F, -v minutes="$minutes" 'NR == 1 { next }
  NR == 2 { t0 = $1 }
  {
    t = ($1 - t0) / 60.0
    if (t <= 5.0) { rss5 = $22; first_sum += $20; first_n++ }
    if (t >= minutes - 5.0) { last_sum += $20; last_n++ }
    rss_end = $22; recoveries += $21; scans++
  }
  END {
    printf "scans %d, recoveries %d\n", scans, recoveries
    printf "peak RSS: %.1f MiB at 5 min, %.1f MiB at %.0f min\n", rss5, rss_end, t
    if (first_n && last_n)
      printf "time per scan: %.2f ms over the first 5 min, %.2f ms over the last 5 min\n",
             first_sum / first_n, last_sum / last_n
  }' "$out/details.csv" | tee "$out/long-run.txt"
