#!/usr/bin/env bash
# Installs every Debian package shatter needs to build, test and run. Idempotent: packages
# already present are skipped, and apt is only called (once) when something is missing.
#   scripts/install-deps.sh          what `make demo` and `make test` need
#   scripts/install-deps.sh --fuzz   also clang, libFuzzer and llvm-symbolizer (`make fuzz`)
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake ninja-build pkg-config
  # a compiler cache: a second clone on the same machine builds from it (CMakeLists.txt)
  ccache
  # prescore: mesh I/O, tetrahedralization, repair
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev libassimp-dev
  # prescore: simplifying very large surfaces for drawing
  libmeshoptimizer-dev
  # simulate
  libbullet-dev libeigen3-dev
  # render
  libosmesa6-dev libpng-dev zlib1g-dev
  # textures: PNG, JPEG and TGA decoding (stb_image), WebP (glTF's EXT_texture_webp); the charts'
  # text (stb_truetype)
  libstb-dev libwebp-dev
  # meshes in an archive: ZIP, 7z, RAR, tar (libarchive)
  libarchive-dev
  # core: logging, CLI, shot files, JSON
  libspdlog-dev libfmt-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev
  # tests
  libgtest-dev
  # the demo mesh (/usr/share/glmark2/models/bunny.obj) and the mesh corpus (scripts/corpus.py):
  # CGAL's data set (data.tar.gz in libcgal-demo) and assimp's test models of every format
  glmark2-data libcgal-demo assimp-testmodels
  # pipeline: MP4 encoding, the energy plots' font (DejaVu Sans, drawn by stb_truetype), the
  # study's charts (Debian's /usr/bin/python3), Slurm fan-out (tested against a single-node
  # cluster on loopback)
  ffmpeg fonts-dejavu-core python3-matplotlib python3-numpy slurm-wlm munge
  # the report pages' tests: headless Chromium opens them (tests/pipeline/report_page_test.cpp)
  chromium
  # the Blender add-on's test: Debian's Blender, headless (tests/blender/); xvfb gives Blender a
  # window on a virtual display for the screenshot in docs/blender.md (make blender-screenshot)
  blender xvfb
)

if [ "${1:-}" = "--fuzz" ]; then
  PACKAGES=(clang libclang-rt-14-dev llvm)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: done"
