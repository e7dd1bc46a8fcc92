#!/usr/bin/env bash
# Installs the Node.js tools the tests use into BUILD_DIR/node_modules (default: build):
# the Khronos glTF validator (npm package gltf-validator), which tests/pipeline/glb_test.cpp
# runs on the .glb export. Idempotent: nothing is fetched when the pinned version is present.
# Never fails: without npm, or without the registry, it says so and the validator test skips.
set -uo pipefail

BUILD_DIR="${1:-build}"
PACKAGE=gltf-validator
VERSION=2.0.0-dev.3.10

installed="$BUILD_DIR/node_modules/$PACKAGE/package.json"
if [ -f "$installed" ] && grep -q "\"version\": *\"$VERSION\"" "$installed"; then
  exit 0
fi
if ! command -v npm > /dev/null 2>&1 || ! command -v node > /dev/null 2>&1; then
  echo "install-node-tools: node/npm not found; the glTF validator test will be skipped" \
       "(fix: apt-get install nodejs npm)"
  exit 0
fi
mkdir -p "$BUILD_DIR"
echo "install-node-tools: installing $PACKAGE@$VERSION into $BUILD_DIR/node_modules"
# --prefix with --no-save: no package.json or lock file is written; a short timeout and no
# retries, so that an unreachable registry costs seconds, not minutes.
log="$BUILD_DIR/install-node-tools.log"
if ! timeout 300 npm install --prefix "$BUILD_DIR" --no-save --no-audit --no-fund --no-package-lock \
       --loglevel=error --fetch-retries=0 --fetch-timeout=60000 "$PACKAGE@$VERSION" > "$log" 2>&1; then
  echo "install-node-tools: npm install failed ($(grep -m1 -E 'npm error (code|network|FetchError)' "$log" || true));" \
       "the glTF validator test will be skipped (details: $log)"
fi
exit 0
