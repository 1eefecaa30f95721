#!/usr/bin/env bash
# zscan set-up, shared by tools/render-demo.sh and tools/run-tests.sh:
# installs the Debian packages the build and tests need when any is missing
# (as root, with apt-get; `apt-get update` first), then configures and
# builds in $ZS_BUILD_DIR (default build/).
#
# Environment:
#   ZS_BUILD_DIR     build directory (default: build)
#   ZS_BUILD_TYPE    CMake build type (default: Release)
#   ZS_CMAKE_ARGS    extra CMake arguments (e.g. -DZS_SANITIZE=ON)
#   CC               the compiler (default: cc)
set -euo pipefail

zs_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

# What each package is for:
#   cmake gcc make pkg-config   the build
#   g++                         the C++ example and the test that the headers compile as C++
#   libpng-dev                  PNG output (lib/image.c)
#   libjpeg62-turbo-dev         JPEG textures (scene/texture_file.c)
#   check                       the unit-test framework (tests/)
#   clang                       the second compiler CI builds and sanitizes with
#   libcjson-dev                scene files (JSON) and statistics
#   libassimp-dev               model formats beyond OBJ (PLY, STL, OFF, glTF...)
#   assimp-testmodels           real and deliberately broken models for the tests
#   gnuplot-nox                 the benchmark plots
#   libosmesa6-dev              Mesa's llvmpipe, for the cross-check test
#   valgrind                    instruction counts: zscan bench raster --callgrind and its test
#   chromium                    headless, reads the pages zscan writes (the golden report) in tests
#   python3-pytest python3-numpy   the Python binding's tests (python/)
zs_packages=(cmake gcc g++ make pkg-config libpng-dev libjpeg62-turbo-dev check clang libcjson-dev
             libassimp-dev assimp-testmodels gnuplot-nox libosmesa6-dev valgrind chromium
             python3-pytest python3-numpy)

zs_missing=()
for p in "${zs_packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    zs_missing+=("$p")
  fi
done
if [ ${#zs_missing[@]} -gt 0 ]; then
  echo "setup: installing ${zs_missing[*]}" >&2
  if [ "$(id -u)" -ne 0 ]; then
    echo "setup: missing packages (${zs_missing[*]}) and not root: install them with apt-get" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${zs_missing[@]}" >&2
fi

ZS_BUILD_DIR=${ZS_BUILD_DIR:-"$zs_root/build"}
ZS_BUILD_TYPE=${ZS_BUILD_TYPE:-Release}
# shellcheck disable=SC2086
cmake -S "$zs_root" -B "$ZS_BUILD_DIR" -DCMAKE_BUILD_TYPE="$ZS_BUILD_TYPE" \
  -DZS_WERROR=ON ${ZS_CMAKE_ARGS:-} >/dev/null
echo "setup: building in $ZS_BUILD_DIR" >&2
if ! cmake --build "$ZS_BUILD_DIR" -j "$(nproc)" >"$ZS_BUILD_DIR/build.log" 2>&1; then
  cat "$ZS_BUILD_DIR/build.log" >&2
  echo "setup: the build failed (log: $ZS_BUILD_DIR/build.log)" >&2
  exit 1
fi
