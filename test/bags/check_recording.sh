#!/usr/bin/env bash
# `conicloc localize --record` for ctest: a short simulated run localized with and without a
# recording.
# Usage: check_recording.sh CONICLOC WORKDIR CASE
#   CASE: foxglove    the recording reads back with npm @mcap/core (check_recording.mjs) and the
#                     poses are the same as without --record
#         unwritable  --record into a missing directory: a clear error naming the file
# Exit 77 (ctest's skip) when node or the npm packages are not installed.
set -euo pipefail
conicloc=$1
work=$2
case=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work" && cd "$work"

"$conicloc" simulate --out run.pcap --truth truth.tum --duration 1.5 --seed 4 > simulate.log 2>&1
# Tracking from the true first pose (x,y,z, yaw from the quaternion).
init=$(awk '!/^#/ {printf "%s,%s,%s,%.4f", $2, $3, $4, atan2(2*($8*$7+$5*$6), 1-2*($6*$6+$7*$7))*57.29577951; exit}' truth.tum)
options="--pcap run.pcap --init $init --init-sigma 0.3,0.3,20 --threads 1 --seed 5"

case $case in
  foxglove)
    command -v node > /dev/null || { echo "SKIP: node is not installed"; exit 77; }
    "$conicloc" localize $options --out plain.tum > plain.log 2>&1
    "$conicloc" localize $options --out recorded.tum --record run.mcap > record.log 2>&1 ||
      { cat record.log; echo "FAIL: localize --record failed"; exit 1; }
    grep "recording:" record.log
    cmp plain.tum recorded.tum || { echo "FAIL: --record changed the poses"; exit 1; }
    [ "$(wc -l < recorded.tum)" -ge 10 ] || { echo "FAIL: too few poses"; exit 1; }
    status=0
    node "$here/check_recording.mjs" run.mcap recorded.tum || status=$?
    exit $status
    ;;
  unwritable)
    if "$conicloc" localize $options --out poses.tum --record missing/dir/run.mcap > record.log 2>&1
    then
      echo "FAIL: --record into a missing directory succeeded"; exit 1
    fi
    cat record.log
    grep -q "missing/dir/run.mcap.*cannot open for writing" record.log ||
      { echo "FAIL: the error does not name the file"; exit 1; }
    echo "PASS: the unwritable recording is named"
    ;;
esac
