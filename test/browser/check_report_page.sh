#!/usr/bin/env bash
# The report page in a real browser, for ctest: simulates a few seconds in the example building,
# localizes with --report-dir, writes the page with `conicloc report` and opens it in headless
# Chromium (test/browser/report_page.mjs). Exit 77 (ctest's skip) when chromium, node or the npm
# packages of test/js are not installed (scripts/install-deps.sh installs them).
# Usage: check_report_page.sh CONICLOC WORKDIR [SCREENSHOT.png]
set -euo pipefail
conicloc=$1
work=$2
here=$(cd "$(dirname "$0")" && pwd)
shot=${3:-$work/report.png}

chromium=${CHROMIUM:-/usr/bin/chromium}
if [ ! -x "$chromium" ] || ! command -v node >/dev/null ||
  [ ! -d "$here/../js/node_modules/playwright-core" ]; then
  echo "skip: needs $chromium, node and test/js/node_modules/playwright-core (scripts/install-deps.sh)"
  exit 77
fi
rm -rf "$work" && mkdir -p "$work" && cd "$work"

"$conicloc" simulate --out run.pcap --truth truth.tum --duration 3 --seed 1 > simulate.log 2>&1
# Tracking from the true start (x,y,z,yaw_deg of the first truth pose): quick even in the
# sanitizer build; the particles move with the sensor from frame to frame.
init=$(awk '!/^#/ && !done { done = 1; printf "%.4f,%.4f,%.4f,%.3f", $2, $3, $4,
  atan2(2 * ($8 * $7 + $5 * $6), 1 - 2 * ($6 * $6 + $7 * $7)) * 45 / atan2(1, 1) }' truth.tum)
"$conicloc" localize --pcap run.pcap --init "$init" --init-particles 500 --out poses.tum \
  --report-dir report --report-every 2 > localize.log 2>&1
"$conicloc" report --report-dir report --truth truth.tum --out run.html > report.log 2>&1
node "$here/report_page.mjs" run.html "$shot"
