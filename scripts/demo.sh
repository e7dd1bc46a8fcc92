#!/usr/bin/env bash
# make demo: the default shot (assets/bunny.toml) on a real mesh, the Stanford bunny from
# Debian's glmark2-data: prescore -> simulate -> render. Says where the results are.
set -euo pipefail
BUILD=${1:-build}
cd "$(dirname "$0")/.."
SHATTER="$BUILD/bin/shatter"
SHOT=assets/bunny.toml
OUT=out/demo
mkdir -p "$OUT"
start=$(date +%s%N)
"$SHATTER" prescore "$SHOT" -o "$OUT/bunny.model"
"$SHATTER" simulate "$OUT/bunny.model" --shot "$SHOT" -o "$OUT/bunny.traj"
"$SHATTER" render "$OUT/bunny.model" "$OUT/bunny.traj" --shot "$SHOT" -o "$OUT/frames"
"$SHATTER" info "$OUT/bunny.model" > "$OUT/bunny.model.txt"
"$SHATTER" info "$OUT/bunny.traj" > "$OUT/bunny.traj.txt"
end=$(date +%s%N)
ms=$(( (end - start) / 1000000 ))
echo
echo "demo done in $((ms / 1000)).$(printf '%03d' $((ms % 1000))) s (build excluded). Results in $(pwd)/$OUT:"
echo "  frames/frame_*.png   the animation, 1280x720 PNG frames"
echo "  bunny.model          the pieces and constraints (bunny.model.txt: shatter info)"
echo "  bunny.pieces.ply     the pieces, one colour each: open it in MeshLab or Blender"
echo "  bunny.traj           the motion of every piece (bunny.traj.txt: shatter info)"
echo "  bunny.breaks.jsonl   every break: time, pieces, force, stored energy, kicks"
echo "  bunny.energy.csv     kinetic, potential, stored, injected and removed energy per frame"
