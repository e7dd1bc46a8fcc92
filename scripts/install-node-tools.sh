#!/usr/bin/env bash
# Installs the Node.js packages shatter and its tests use into BUILD_DIR/node_modules (default:
# build), each by name and pinned version:
#   gltf-validator  the Khronos glTF validator, which tests/pipeline/glb_test.cpp runs on the .glb;
#   three           three.js (its classic-script build, with GLTFLoader and OrbitControls), the 3D
#                   view of `shatter run`'s report.html: shatter finds it beside its executable
#                   (BUILD/bin/../node_modules/three) and copies it next to the report;
#   puppeteer-core  drives Debian's /usr/bin/chromium in tests/pipeline/report_page_test.cpp.
# Idempotent: nothing is fetched when the pinned versions are present. Never fails: without npm,
# or without the registry, it says so; the report then has no 3D view (and says why) and the
# tests that need a package are skipped.
set -uo pipefail

BUILD_DIR="${1:-build}"
PACKAGES=(gltf-validator@2.0.0-dev.3.10 three@0.147.0 puppeteer-core@24.10.0)

missing=()
for spec in "${PACKAGES[@]}"; do
  name="${spec%@*}"
  version="${spec##*@}"
  installed="$BUILD_DIR/node_modules/$name/package.json"
  if ! { [ -f "$installed" ] && grep -q "\"version\": *\"$version\"" "$installed"; }; then
    missing+=("$spec")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
if ! command -v npm > /dev/null 2>&1 || ! command -v node > /dev/null 2>&1; then
  echo "install-node-tools: node/npm not found; the report has no 3D view and the glTF validator and" \
       "report page tests will be skipped (fix: apt-get install nodejs npm)"
  exit 0
fi
mkdir -p "$BUILD_DIR"
echo "install-node-tools: installing ${missing[*]} into $BUILD_DIR/node_modules"
# --prefix with --no-save: no package.json or lock file is written; a short timeout and no
# retries, so that an unreachable registry costs seconds, not minutes. Every package is named
# (not only the missing ones), so that npm keeps the ones already there.
log="$BUILD_DIR/install-node-tools.log"
if ! timeout 300 npm install --prefix "$BUILD_DIR" --no-save --no-audit --no-fund --no-package-lock \
       --loglevel=error --fetch-retries=0 --fetch-timeout=60000 "${PACKAGES[@]}" > "$log" 2>&1; then
  echo "install-node-tools: npm install failed ($(grep -m1 -E 'npm error (code|network|FetchError)' "$log" || true));" \
       "the report has no 3D view and the tests that need these packages will be skipped (details: $log)"
fi
exit 0
