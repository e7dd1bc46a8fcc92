#!/usr/bin/env bash
# make bench: runs every benchmark and keeps its CSV in bench/results/ (one file per benchmark), then
# makes docs/results/benchmarks.md from the CSVs (scripts/bench_tables.py).
set -euo pipefail
BUILD=${1:-build}
cd "$(dirname "$0")/.."
mkdir -p bench/results
echo "prescore: phase times for the bunny by resolution (bench/results/prescore.csv)"
"$BUILD/bench/prescore_bench" | tee bench/results/prescore.csv
echo "simulate: steps per second and the cost of energizing (bench/results/simulate.csv)"
"$BUILD/bench/simulate_bench" | tee bench/results/simulate.csv
echo "render: frames per second of the bunny at 1280x720, the defaults and other settings, PNG writing included (bench/results/render.csv)"
"$BUILD/bench/render_bench" | tee bench/results/render.csv
echo "demo: the demo job (shatter run assets/bunny.toml) three times, and the same job in Blender beside it when blender is installed (bench/results/demo.csv)"
/usr/bin/python3 scripts/demo_bench.py "$BUILD" | tee bench/results/demo.csv
/usr/bin/python3 scripts/bench_tables.py
