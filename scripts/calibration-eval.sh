#!/usr/bin/env bash
# Calibration accuracy over seeds in the example building: for each seed, simulate a capture with
# per-laser calibration errors, calibrate it against the map, score the estimate against the
# truth, and localize the capture with the nominal, the true and the estimated calibration.
# Prints one markdown table row per seed (the README's table).
#
#   scripts/calibration-eval.sh build/tools/conicloc /tmp/calib-eval 1 2 3 4 5
#   CALIB_SIM_OPTIONS="--mount-pitch-deg 6 --mount-roll-deg 3" CALIB_INIT_TILT=3,6 scripts/...
set -euo pipefail
bin=$1
out=$2
shift 2
seeds=${*:-1 2 3 4 5}
sim_options=${CALIB_SIM_OPTIONS:-}
tilt=${CALIB_INIT_TILT:-0,0}
mkdir -p "$out"

# "x,y,z,yaw_deg" of the first truth pose (TUM: t x y z qx qy qz qw).
first_pose() {
  awk '!/^#/ && NF == 8 { yaw = atan2(2 * ($8 * $7 + $5 * $6), 1 - 2 * ($6 * $6 + $7 * $7));
                          printf "%.4f,%.4f,%.4f,%.3f\n", $2, $3, $4, yaw * 45 / atan2(1, 1); exit }' "$1"
}
ate_xy() { sed -n 's/.*ATE xy *rmse *\([0-9.]*\).*/\1/p' "$1"; }

echo "| seed | elevation RMS (°) | vertical offset RMS (mm) | azimuth RMS (°) | range offset RMS (mm) | unobservable (φ/o/ψ/d) | ATE xy nominal (m) | true (m) | estimated (m) |"
echo "|---|---|---|---|---|---|---|---|---|"
for seed in $seeds; do
  p=$out/s$seed
  "$bin" simulate --out "$p.pcap" --truth "$p.tum" --duration 12 --seed "$seed" \
    --calib-error-deg 0.1 --calib-offset-error-mm 5 --calib-azimuth-error-deg 0.1 \
    --calib-truth "$p.calib-truth.json" --calib-truth-xml "$p.true.xml" $sim_options >"$p.sim.log" 2>&1
  init=$(first_pose "$p.tum")
  "$bin" calibrate --pcap "$p.pcap" --out "$p.cal.xml" --report "$p.cal.json" --truth "$p.true.xml" \
    --init "$init" --init-tilt "$tilt" >"$p.cal.log" 2>&1
  row=$(python3 -c "
import json, sys
t = json.load(open('$p.cal.json'))['truth']
print('| $seed | {:.4f} | {:.2f} | {:.4f} | {:.2f} | {} |'.format(t['elevation_rms_deg'],
      t['vertical_offset_rms_mm'], t['azimuth_offset_rms_deg'], t['range_offset_rms_mm'],
      '/'.join(str(n) for n in t['unobservable'])))")
  for cal in nominal true cal; do
    option=""
    [ "$cal" != nominal ] && option="--calibration $p.$cal.xml"
    "$bin" localize --pcap "$p.pcap" --out "$p.$cal.tum" --init "$init" $option >"$p.$cal.loc.log" 2>&1
    "$bin" evaluate --truth "$p.tum" --est "$p.$cal.tum" >"$p.$cal.eval.log" 2>&1
    row="$row $(ate_xy "$p.$cal.eval.log") |"
  done
  echo "$row"
done
