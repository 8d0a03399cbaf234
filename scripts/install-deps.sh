#!/usr/bin/env bash
# Installs every build and test dependency of conicloc from Debian's archive, and the tests' MCAP
# writer and browser driver (playwright-core) from the npm registry (pinned by
# test/js/package-lock.json).
# Idempotent: quiet and quick when everything is already there.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake ninja-build g++ pkg-config
  libeigen3-dev libgeographiclib-dev libpugixml-dev libnanoflann-dev libspdlog-dev libfmt-dev
  libpcap-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  libzstd-dev liblz4-dev libbz2-dev libsqlite3-dev
  tcpdump
  # Independent bag writers of the tests: ROS 1 bags (rosbag; lz4 chunks need roslz4) and, with
  # node, the reference MCAP library (npm @mcap/core).
  python3-rosbag python3-roslz4 python3-genpy nodejs
  # The report page's browser test: Debian's Chromium, driven by npm playwright-core (test/js).
  chromium
  # A one-machine Slurm cluster and GNU parallel for the sharded-sweep tests (test/cluster/).
  slurm-wlm munge parallel
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Debian's npm conflicts with other builds of nodejs that bring their own npm.
command -v npm >/dev/null || missing+=(npm)

if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "install-deps: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
fi

js=test/js
if [ ! -f "$js/node_modules/.package-lock.json" ] ||
  [ "$js/package-lock.json" -nt "$js/node_modules/.package-lock.json" ]; then
  echo "install-deps: npm ci in $js"
  (cd "$js" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
fi
