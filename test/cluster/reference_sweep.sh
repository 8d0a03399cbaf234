#!/usr/bin/env bash
# ctest fixture: the unsharded quick sweep the sharded ones are compared with.
# Usage: reference_sweep.sh CONICLOC OUT_DIR
set -euo pipefail
if ! command -v sbatch >/dev/null && ! command -v parallel >/dev/null; then
  echo "SKIP: neither Slurm (sbatch) nor GNU parallel is installed"
  exit 77
fi
rm -rf "$2"
"$1" evaluate --sweep quick --out "$2"
