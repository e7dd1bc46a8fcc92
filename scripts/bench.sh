#!/usr/bin/env bash
# make bench: runs every benchmark and keeps its CSV in bench/results/ (one file per benchmark).
set -euo pipefail
BUILD=${1:-build}
cd "$(dirname "$0")/.."
mkdir -p bench/results
echo "prescore: phase times for the bunny by resolution (bench/results/prescore.csv)"
"$BUILD/bench/prescore_bench" | tee bench/results/prescore.csv
