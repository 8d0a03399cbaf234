#!/usr/bin/env bash
# The main job on the shipped example building: summarise the map, simulate a VLP-16 walking
# through it, localize on the simulated capture, report pose error against ground truth, and write
# the run's interactive HTML report (open OUT_DIR/run.html in a browser; it needs no network).
# Usage: scripts/demo.sh [OUT_DIR]   (default out/demo)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/demo}
mkdir -p "$out"

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target conicloc --parallel "$(nproc)"
conicloc=build/tools/conicloc

echo "== 1. The example building"
$conicloc map-info
$conicloc map-export --svg "$out/floorplan.svg" --obj "$out/building.obj"

echo "== 2. Simulate 30 s of a robot-mounted VLP-16 along the navigation graph (up the stair)"
$conicloc simulate --out "$out/run.pcap" --truth "$out/truth.tum" --odom "$out/odom.tum" \
  --duration 30 --seed 1

echo "== 3. Localize from a global start: no initial pose, no odometry (conic-beam model)"
# The filter spreads its particles over every navigable cell of the building, measures its own
# motion from the scans, and logs when its status first becomes 'tracking' (converged).
$conicloc localize --pcap "$out/run.pcap" --global --height 0.8 --model conic-beam \
  --out "$out/poses.tum" --details "$out/details.csv" --covariance "$out/covariance.csv" \
  --report-dir "$out/report"

echo "== 4. Pose error against ground truth"
$conicloc evaluate --truth "$out/truth.tum" --est "$out/poses.tum" --errors "$out/errors.csv"
echo "== 5. The run's report: floor plans, particles and predicted conics over time, plots, summary"
$conicloc report --report-dir "$out/report" --truth "$out/truth.tum" --out "$out/run.html"
echo "outputs in $out/; open the report in a browser: file://$(cd "$out" && pwd)/run.html"
