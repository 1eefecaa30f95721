#!/usr/bin/env bash
# zscan set-up, shared by tools/render-demo.sh and tools/run-tests.sh:
# installs the Debian packages the build and tests need when any is missing
# (as root, with apt-get; `apt-get update` first), then configures and
# builds in $ZS_BUILD_DIR (default build/).
#
# With ZS_CROSS (targets, e.g. "aarch64 s390x i686"), also what
# tools/cross-check.sh needs: each target's cross compiler, qemu-user, and
# its libraries from Debian's packages, unpacked (apt-get download,
# dpkg-deb -x) into $ZS_CROSS_ROOT/TARGET, where multiarch installs would
# clash with the native ones' versions.
#
# Environment:
#   ZS_CROSS         cross targets to set up (default: none)
#   ZS_CROSS_ROOT    where their libraries go (default: /opt/zscan-cross)
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
#   python3-venv python3-pip python3-setuptools python3-wheel
#                               the Python package built and installed offline
#                               into a fresh virtual environment (tools/check-wheel.sh)
zs_packages=(cmake gcc g++ make pkg-config libpng-dev libjpeg62-turbo-dev check clang libcjson-dev
             libassimp-dev assimp-testmodels gnuplot-nox libosmesa6-dev valgrind chromium
             python3-pytest python3-numpy python3-venv python3-pip python3-setuptools
             python3-wheel)

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

# shellcheck source=tools/cross-targets.sh
. "$zs_root/tools/cross-targets.sh"
# What the library and its golden test link against on the target (no
# assimp: its dependencies are many, and the goldens of its formats are
# checked natively)
zs_cross_libs=(libpng-dev libpng16-16 libjpeg62-turbo-dev libjpeg62-turbo libcjson-dev libcjson1
               zlib1g zlib1g-dev check libsubunit-dev libsubunit0)
if [ -n "${ZS_CROSS:-}" ]; then
  zs_cross_root=${ZS_CROSS_ROOT:-/opt/zscan-cross}
  zs_need=()
  zs_missing_cross=()
  for t in $ZS_CROSS; do
    zs_cross_target "$t" >/dev/null || exit 2
    read -r deb triplet _ _ <<<"$(zs_cross_target "$t")"
    [ -d "$zs_cross_root/$t/usr" ] || zs_need+=("$t")
    command -v "$triplet-gcc" >/dev/null || zs_missing_cross+=("gcc-$triplet")
    [ -e "/usr/$triplet/lib/crti.o" ] || zs_missing_cross+=("libc6-dev-$deb-cross")
    dpkg --print-foreign-architectures | grep -qx "$deb" || dpkg --add-architecture "$deb"
  done
  command -v qemu-aarch64-static >/dev/null || zs_missing_cross+=(qemu-user-static)
  if [ ${#zs_missing_cross[@]} -gt 0 ] || [ ${#zs_need[@]} -gt 0 ]; then
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
  fi
  if [ ${#zs_missing_cross[@]} -gt 0 ]; then
    echo "setup: installing ${zs_missing_cross[*]}" >&2
    apt-get install -y -qq --no-install-recommends "${zs_missing_cross[@]}" >&2
  fi
  for t in "${zs_need[@]}"; do
    read -r deb _ _ _ <<<"$(zs_cross_target "$t")"
    echo "setup: the $t libraries into $zs_cross_root/$t" >&2
    zs_debs=$(mktemp -d)
    (cd "$zs_debs" && apt-get download -qq "${zs_cross_libs[@]/%/:$deb}") >&2
    rm -rf "$zs_cross_root/$t.part"
    mkdir -p "$zs_cross_root/$t.part"
    for d in "$zs_debs"/*.deb; do dpkg-deb -x "$d" "$zs_cross_root/$t.part"; done
    rm -rf "$zs_debs"
    mv "$zs_cross_root/$t.part" "$zs_cross_root/$t" # whole, or not at all
  done
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
