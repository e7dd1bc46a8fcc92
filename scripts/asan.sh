#!/usr/bin/env bash
# `make asan`: builds shatter and every test with AddressSanitizer + UndefinedBehaviorSanitizer
# (gcc, -O1, frame pointers kept) into BUILD_DIR (default build-asan) and runs the whole test
# suite there. Any sanitizer report fails the run: halt_on_error makes the reporting process
# exit non-zero, and every test (including the ones that drive the instrumented `shatter`
# binary) checks exit codes. docs/reliability.md says what it costs and what CI runs.
#
#   bash scripts/asan.sh [BUILD_DIR] [JOBS] [CTEST_ARGS...]
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD_DIR="${1:-build-asan}"
JOBS="${2:-2}"
shift $(( $# > 2 ? 2 : $# ))

# -O1: fast enough to run the physics tests, keeps stacks readable. -g1: line tables only
# (full -g makes a CGAL translation unit cost ~6 GB). CGAL files still compile one at a time
# in the heavy job pool (CMakeLists.txt), at their own -O2.
SAN="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
start=$(date +%s)
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=None \
  -DCMAKE_C_FLAGS="-O1 -g1 $SAN" -DCMAKE_CXX_FLAGS="-O1 -g1 $SAN" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" > "$BUILD_DIR.configure.log" 2>&1 \
  || { cat "$BUILD_DIR.configure.log"; exit 1; }
cmake --build "$BUILD_DIR" -j "$JOBS"
built=$(date +%s)
echo "asan: build took $((built - start)) s"

bash scripts/install-node-tools.sh "$BUILD_DIR"

# Every process the tests start inherits these: halt at the first report, print its stack,
# symbolize it, and fail (exit 1 from the sanitizer runtime is what the tests see).
export ASAN_OPTIONS="halt_on_error=1:print_stacktrace=1:detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=0:suppressions=$PWD/tests/sanitizers/asan.supp"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$PWD/tests/sanitizers/ubsan.supp"
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0"
if command -v llvm-symbolizer > /dev/null 2>&1; then export ASAN_SYMBOLIZER_PATH="$(command -v llvm-symbolizer)"; fi
log="$BUILD_DIR/asan-ctest.log"
status=0
# Imports run ~20x slower under ASan than the reader's deadline allows for (meshio/mesh_load.cpp).
export SHATTER_MESH_IMPORT_TIMEOUT=${SHATTER_MESH_IMPORT_TIMEOUT:-600}
(cd "$BUILD_DIR" && ctest --output-on-failure -j "$JOBS" --timeout 900 "$@") 2>&1 | tee "$log" || status=$?
done_at=$(date +%s)
reports=$(grep -cE '^(==[0-9]+==ERROR: (AddressSanitizer|LeakSanitizer)|.*runtime error:)' "$log" || true)
echo "asan: tests took $((done_at - built)) s; sanitizer reports in the output: $reports (log: $log)"
if [ "$reports" -ne 0 ]; then exit 1; fi
exit "$status"
