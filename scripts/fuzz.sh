#!/usr/bin/env bash
# Runs the libFuzzer harnesses of fuzz/ for a set time each, one after the other.
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]      (default: 60 s, every fuzz/fuzz_*.cpp)
#   e.g. scripts/fuzz.sh 600 indoorgml capture_reader
#        scripts/fuzz.sh 60 mcap_reader rosbag1_reader ros2_db3_reader velodyne_scan_msg
#
# Configures and builds an instrumented clang build (ASan + UBSan + libFuzzer coverage on the
# conicloc libraries too) in $CONICLOC_FUZZ_BUILD_DIR (default build-fuzz), assembles each
# target's corpus from fuzz/corpus/<target>, test/data, examples/ and slices of ../shared/data
# (copied under the build dir, never into the repo), then runs each fuzzer with
# -max_total_time. A hang (> $FUZZ_TIMEOUT_S per input) or memory over $FUZZ_RSS_MB is a finding
# like a crash. Findings go to <build>/findings/<target>/; the exit status is non-zero if any
# fuzzer found something. Logs: <build>/fuzz-logs/<target>.log. $FUZZ_NICE (default 10) is the
# niceness of the runs.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${CONICLOC_FUZZ_BUILD_DIR:-$root/build-fuzz}"
seconds="${1:-60}"
shift || true
timeout_s="${FUZZ_TIMEOUT_S:-10}"
rss_mb="${FUZZ_RSS_MB:-2048}"
niceness="${FUZZ_NICE:-10}"

if ! [[ "$seconds" =~ ^[0-9]+$ ]]; then
  echo "usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]" >&2
  exit 2
fi
targets=()
if (($# == 0)); then
  for source in "$root"/fuzz/fuzz_*.cpp; do targets+=("$(basename "$source" .cpp)"); done
else
  for name in "$@"; do targets+=("fuzz_${name#fuzz_}"); done
fi
for target in "${targets[@]}"; do
  if [[ ! -f "$root/fuzz/$target.cpp" ]]; then
    echo "fuzz.sh: no harness fuzz/$target.cpp" >&2
    exit 2
  fi
done

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER=clang++ "${launcher[@]}" \
  -DCONICLOC_BUILD_FUZZERS=ON -DCONICLOC_BUILD_TESTS=OFF -DCONICLOC_BUILD_BENCHMARKS=OFF \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g" \
  "-DCMAKE_CXX_FLAGS=-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -D_GLIBCXX_ASSERTIONS" \
  "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined" >/dev/null
nice -n "$niceness" cmake --build "$build" -j2 --target "${targets[@]}"

# Seeds: regenerated every run (the committed ones, the test inputs, shared slices if present).
seeds="$build/fuzz-seeds"
rm -rf "$seeds"
mkdir -p "$seeds"
shared_args=()
[[ -d "$root/../shared/data" ]] && shared_args=(--shared "$root/../shared/data")
python3 "$root/fuzz/seed_corpora.py" "$seeds" "${shared_args[@]}"
# The committed seeds of every target (the bags written by independent writers among them).
for committed in "$root"/fuzz/corpus/*/; do
  name="$(basename "$committed")"
  mkdir -p "$seeds/$name"
  cp "$committed"* "$seeds/$name/"
done
cp "$root"/test/data/indoorgml/*.gml "$root/examples/example_building.gml" "$seeds/fuzz_indoorgml/"
for calibration in "$root"/../shared/data/velodyne/veloview-*.xml; do
  [[ -e "$calibration" ]] && cp "$calibration" "$seeds/fuzz_veloview_calibration/"
done
for regression in "$root"/test/data/fuzz_regressions/*; do
  [[ -e "$regression" ]] || continue
  name="$(basename "$regression")"
  target="fuzz_${name%%-*}"  # regression files are named <target>-<what>
  [[ -d "$seeds/$target" ]] && cp "$regression" "$seeds/$target/"
done

status=0
summary=()
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  findings="$build/findings/$target"
  log="$build/fuzz-logs/$target.log"
  mkdir -p "$corpus" "$findings" "$(dirname "$log")" "$seeds/$target"
  extra=()
  case "$target" in
    fuzz_indoorgml) extra=(-dict="$root/fuzz/gml.dict" -max_len=80000) ;;
    fuzz_capture_reader) extra=(-max_len=16384) ;;
    fuzz_velodyne_decoder) extra=(-max_len=1400 -use_value_profile=1) ;;
    fuzz_trajectory_text) extra=(-max_len=4096) ;;
    fuzz_veloview_calibration) extra=(-max_len=50000) ;;
    fuzz_mcap_reader | fuzz_rosbag1_reader | fuzz_ros2_db3_reader) extra=(-max_len=16384) ;;
    fuzz_velodyne_scan_msg) extra=(-max_len=4096) ;;
  esac
  echo "== $target: ${seconds} s (log $log)"
  set +e
  nice -n "$niceness" "$build/fuzz/$target" "$corpus" "$seeds/$target" \
    -max_total_time="$seconds" -timeout="$timeout_s" -rss_limit_mb="$rss_mb" \
    -artifact_prefix="$findings/" -print_final_stats=1 "${extra[@]}" >"$log" 2>&1
  code=$?
  set -e
  stats="$(grep -E '^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)' "$log" |
    sed 's/^stat:://' | tr '\n' ' ')"
  coverage="$(grep -E '^#[0-9]+' "$log" | tail -1 | grep -oE 'cov: [0-9]+ ft: [0-9]+ corp: [^ ]+' || true)"
  if ((code != 0)); then
    status=1
    summary+=("$target: FINDING (exit $code) $stats $coverage; see $log and $findings/")
    grep -E 'ERROR: |SUMMARY: |Test unit written' "$log" | head -5 || true
  else
    summary+=("$target: ok $stats $coverage")
  fi
done

echo "== summary"
printf '%s\n' "${summary[@]}"
exit "$status"
