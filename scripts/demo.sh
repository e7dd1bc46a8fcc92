#!/usr/bin/env bash
# make demo: the default job on a real mesh (the Stanford bunny from Debian's glmark2-data).
set -euo pipefail
BUILD=${1:-build}
cd "$(dirname "$0")/.."
OUT=out/demo
mkdir -p "$OUT"
start=$(date +%s%N)
"$BUILD/bin/shatter" prescore assets/bunny.toml -o "$OUT/bunny.model"
"$BUILD/bin/shatter" info "$OUT/bunny.model" > "$OUT/bunny.info.txt"
end=$(date +%s%N)
ms=$(( (end - start) / 1000000 ))
echo
echo "demo done in $((ms / 1000)).$(printf '%03d' $((ms % 1000))) s. Results in $(pwd)/$OUT:"
echo "  bunny.model        the pieces and constraints (shatter info $OUT/bunny.model)"
echo "  bunny.pieces.ply   the pieces, one colour each: open it in MeshLab or Blender"
echo "  bunny.info.txt     the model summary"
