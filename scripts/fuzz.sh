#!/usr/bin/env bash
# `make fuzz`: builds the libFuzzer targets (tests/fuzz/, clang with ASan + UBSan) into BUILD_DIR
# and fuzzes each one for SECONDS on a working copy of its seed corpus. A crash, a sanitizer
# report, a leak, an uncaught exception, or an input slower than 10 s ends that target's run and
# leaves the input in BUILD_DIR/run/TARGET/artifacts/; the script then exits 1. Fix the reader,
# and copy the input to tests/fuzz/regressions/TARGET/ so that ctest replays it (docs/reliability.md).
#
#   bash scripts/fuzz.sh [SECONDS] [BUILD_DIR] [JOBS] [TARGET...]   (defaults: 60 build-fuzz 2, every target)
#   FUZZ_ARGS="-seed=1" adds libFuzzer flags (CI fixes the seed so that a run can be repeated).
set -euo pipefail
cd "$(dirname "$0")/.."

SECONDS_PER_TARGET="${1:-60}"
BUILD_DIR="${2:-build-fuzz}"
JOBS="${3:-2}"
shift $(( $# > 3 ? 3 : $# ))
TARGETS=("$@")
if [ ${#TARGETS[@]} -eq 0 ]; then TARGETS=(mesh gltf archive shot batch model trajectory logs png); fi

bash scripts/install-deps.sh > /dev/null
bash scripts/install-deps.sh --fuzz > /dev/null
# Through ccache where installed, as the main build (CMakeLists.txt): paths relative to the
# source folder, so a second clone on the machine compiles from the cache.
LAUNCHER=()
if command -v ccache > /dev/null; then
  LAUNCHER=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="$(pwd)" CCACHE_NOHASHDIR=true
fi
if [ ! -f "$BUILD_DIR/build.ninja" ]; then
  CC=clang CXX=clang++ cmake -S tests/fuzz -B "$BUILD_DIR" -G Ninja "${LAUNCHER[@]}" > "$BUILD_DIR.configure.log" 2>&1 \
    || { cat "$BUILD_DIR.configure.log"; exit 1; }
fi
start=$(date +%s)
cmake --build "$BUILD_DIR" -j "$JOBS" -- $(printf '%s_fuzz ' "${TARGETS[@]}")
echo "fuzz: build took $(( $(date +%s) - start )) s"

export ASAN_OPTIONS="detect_leaks=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
if command -v llvm-symbolizer > /dev/null 2>&1; then export ASAN_SYMBOLIZER_PATH="$(command -v llvm-symbolizer)"; fi
report="$BUILD_DIR/fuzz-report.txt"
: > "$report"
failed=0
for t in "${TARGETS[@]}"; do
  work="$BUILD_DIR/run/$t"
  mkdir -p "$work/corpus" "$work/artifacts"
  cp -n tests/fuzz/corpus/"$t"/* "$work/corpus/" 2> /dev/null || true
  log="$work/fuzz.log"
  t0=$(date +%s)
  status=0
  # -timeout: an input slower than 10 s is a hang; -rss_limit_mb: more than 2 GB is a finding
  # (a reader must never allocate what the file cannot hold).
  "$BUILD_DIR/${t}_fuzz" -max_total_time="$SECONDS_PER_TARGET" -timeout=10 -rss_limit_mb=2048 \
      -print_final_stats=1 -artifact_prefix="$work/artifacts/" ${FUZZ_ARGS:-} "$work/corpus" > "$log" 2>&1 || status=$?
  took=$(( $(date +%s) - t0 ))
  runs=$(grep -oE 'stat::number_of_executed_units: *[0-9]+' "$log" | tail -1 | grep -oE '[0-9]+$' || echo "?")
  units=$(ls "$work/corpus" | wc -l)
  if [ "$status" -eq 0 ]; then
    line="$t: clean for ${took} s, ${runs} runs, corpus ${units} inputs"
  else
    failed=1
    line="$t: FINDING after ${took} s (exit $status): $(ls -t "$work/artifacts" | head -1) -- see $log"
    grep -m3 -E 'ERROR: |runtime error|fuzz: |deadly signal|Timeout|out-of-memory|uncaught' "$log" | sed 's/^/    /' || true
  fi
  echo "$line" | tee -a "$report"
done
echo "fuzz: report in $report"
exit "$failed"
