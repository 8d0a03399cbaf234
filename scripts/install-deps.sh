#!/usr/bin/env bash
# Installs every build and test dependency of conicloc from Debian's archive.
# Idempotent: quiet and quick when everything is already there.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  libeigen3-dev libgeographiclib-dev libpugixml-dev libnanoflann-dev libspdlog-dev libfmt-dev
  libpcap-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  tcpdump
  slurm-wlm munge parallel
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
