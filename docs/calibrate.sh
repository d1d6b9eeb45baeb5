#!/bin/sh
# Regenerate the calibration table of docs/validation.md: run the quick
# validation suite with 40 seeds (about 70 minutes on one core), keep the
# per-record lines as docs/calibration-quick.csv and rewrite the table
# between the calibration markers.
#
#   docs/calibrate.sh [SMOLBRIDGE] [SEEDS]
#   SB_LAUNCH="mpirun -n 2" docs/calibrate.sh ./smolbridge   (an MPI build
#   shares the seeds between ranks and writes the same files: docs/parallel.md)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
sb=${1:-./smolbridge}
n=${2:-40}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
${SB_LAUNCH:-} "$sb" validate --seeds "$n" --out "$out" > "$out/stdout.txt" || true
cp "$out/calibration.csv" "$here/calibration-quick.csv"
python3 "$here/calibration_table.py" "$out/calibration.csv" \
  "$here/validation.md" "$n"
echo "docs/validation.md and docs/calibration-quick.csv updated"
