#!/usr/bin/env bash
# Calibration accuracy over seeds in the example building: for each seed, simulate a capture with
# per-laser calibration errors, calibrate it against the map, score the estimate against the
# truth, and localize the capture with the nominal, the true and the estimated calibration.
# Prints one markdown table row per seed (the README's table).
#
#   scripts/calibration-eval.sh build/tools/conicloc /tmp/calib-eval 1 2 3 4 5
#   CALIB_SIM_OPTIONS="--mount-pitch-deg 6 --mount-roll-deg 3" CALIB_INIT_TILT=3,6 scripts/...
# CALIB_MAP=FILE runs it in another building (simulate, calibrate and localize --map FILE).
# CALIB_DURATION (12 s) and CALIB_SCANS (60) set the capture's length and the scans calibrate uses.
# With CALIB_SECOND_SENSOR="x,y,z,roll_deg,pitch_deg,yaw_deg" a second VLP-16 rides along
# (simulate --second-sensor) and a second table gives its pose found by calibrate
# --second-sensor (nothing known of it), estimate - truth +- the reported sigma.
set -euo pipefail
bin=$1
out=$2
shift 2
seeds=${*:-1 2 3 4 5}
sim_options=${CALIB_SIM_OPTIONS:-}
tilt=${CALIB_INIT_TILT:-0,0}
duration=${CALIB_DURATION:-12}
scans=${CALIB_SCANS:-60}
second=${CALIB_SECOND_SENSOR:-}
map_option=""
[ -n "${CALIB_MAP:-}" ] && map_option="--map $CALIB_MAP"
second_sim=""
second_cal=""
if [ -n "$second" ]; then
  second_sim="--second-sensor $second"
  second_cal="--second-sensor 192.168.1.202:2369"
fi
second_rows=""
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
  "$bin" simulate $map_option --out "$p.pcap" --truth "$p.tum" --duration "$duration" --seed "$seed" \
    --calib-error-deg 0.1 --calib-offset-error-mm 5 --calib-azimuth-error-deg 0.1 \
    --calib-truth "$p.calib-truth.json" --calib-truth-xml "$p.true.xml" $sim_options $second_sim \
    >"$p.sim.log" 2>&1
  init=$(first_pose "$p.tum")
  "$bin" calibrate $map_option --pcap "$p.pcap" --out "$p.cal.xml" --report "$p.cal.json" --truth "$p.true.xml" \
    --init "$init" --init-tilt "$tilt" --scans "$scans" $second_cal >"$p.cal.log" 2>&1
  row=$(python3 -c "
import json, sys
t = json.load(open('$p.cal.json'))['truth']
print('| $seed | {:.4f} | {:.2f} | {:.4f} | {:.2f} | {} |'.format(t['elevation_rms_deg'],
      t['vertical_offset_rms_mm'], t['azimuth_offset_rms_deg'], t['range_offset_rms_mm'],
      '/'.join(str(n) for n in t['unobservable'])))")
  for cal in nominal true cal; do
    option=""
    [ "$cal" != nominal ] && option="--calibration $p.$cal.xml"
    "$bin" localize $map_option --pcap "$p.pcap" --out "$p.$cal.tum" --init "$init" $option >"$p.$cal.loc.log" 2>&1
    "$bin" evaluate --truth "$p.tum" --est "$p.$cal.tum" >"$p.$cal.eval.log" 2>&1
    row="$row $(ate_xy "$p.$cal.eval.log") |"
  done
  echo "$row"
  if [ -n "$second" ]; then
    second_rows="$second_rows$(python3 -c "
import json
truth = json.load(open('$p.calib-truth.json'))['second_sensor']
e = json.load(open('$p.cal.json'))['second_sensor']
cells = []
for key, scale in (('x_m', 1000), ('y_m', 1000), ('z_m', 1000), ('roll_deg', 1), ('pitch_deg', 1), ('yaw_deg', 1)):
    sigma = key.replace('_m', '_sigma_m') if key.endswith('_m') else key.replace('_deg', '_sigma_deg')
    cells.append('n/a' if e[key] is None else '{:+.3g} ± {:.2g}'.format((e[key] - truth[key]) * scale, e[sigma] * scale))
print('| $seed | ' + ' | '.join(cells) + ' | {} |'.format(e['returns']))")
"
  fi
done
if [ -n "$second" ]; then
  echo
  echo "| seed | x (mm) | y (mm) | z (mm) | roll (°) | pitch (°) | yaw (°) | returns |"
  echo "|---|---|---|---|---|---|---|---|"
  printf "%s" "$second_rows"
fi
