#!/usr/bin/env bash
# make demo: the default shot (assets/bunny.toml) on a real mesh, the Stanford bunny from
# Debian's glmark2-data, from mesh to movie with `shatter run`. Says where the results are: the
# page out/demo/report.html shows them all (its 3D view needs three.js, which `make demo` installs
# with scripts/install-node-tools.sh).
set -euo pipefail
BUILD=${1:-build}
cd "$(dirname "$0")/.."
OUT=out/demo
start=$(date +%s%N)
status=0
"$BUILD/bin/shatter" run assets/bunny.toml -o "$OUT" || status=$?
end=$(date +%s%N)
ms=$(( (end - start) / 1000000 ))
echo
if [ "$status" -ne 0 ]; then
  echo "demo FAILED (exit code $status); the log is $(pwd)/$OUT/run.log"
  exit "$status"
fi
echo "demo done in $((ms / 1000)).$(printf '%03d' $((ms % 1000))) s (build excluded; up-to-date stages are skipped)."
echo "The page with everything (movie, contact sheet, energy plot, numbers, 3D view): open $(pwd)/$OUT/report.html"
echo "The movie: $(pwd)/$OUT/bunny.mp4"
