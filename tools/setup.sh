#!/usr/bin/env bash
# zscan set-up, shared by tools/render-demo.sh and tools/run-tests.sh:
# installs the Debian packages the build and tests need when any is missing
# (as root, with apt-get; `apt-get update` first), then configures and
# builds in $ZS_BUILD_DIR (default build/).
#
# With ZS_CROSS (targets, e.g. "aarch64 s390x i686 musl"), also what
# tools/cross-check.sh needs: each target's cross compiler, qemu-user, and
# its libraries from Debian's packages, unpacked (apt-get download,
# dpkg-deb -x) into $ZS_CROSS_ROOT/TARGET, where multiarch installs would
# clash with the native ones' versions; for musl, musl-gcc and the
# libraries built from Debian's sources into $ZS_MUSL_ROOT; for windows,
# mingw-w64 and wine, and the libraries built from Debian's sources with
# mingw-w64 into $ZS_WINDOWS_ROOT (with its CMake toolchain file).
#
# Environment:
#   ZS_CROSS         cross targets to set up (default: none)
#   ZS_CROSS_ROOT    where their libraries go (default: /opt/zscan-cross)
#   ZS_WASM_ROOT     cJSON's sources for the teaching page's engine (default: /opt/zscan-wasm)
#   ZS_MUSL_ROOT     the musl target's libraries (default: /opt/zscan-musl)
#   ZS_WINDOWS_ROOT  the windows target's libraries (default: /opt/zscan-windows)
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
#   emscripten                  the teaching page's engine: zscan's trace in WebAssembly
#   dpkg-dev                    apt-get source: cJSON's sources, which the engine builds
#   nodejs npm                  the teaching page's browser tests (tests/web), and emcc's
#                               own tools (only when node or npm is missing: a Node.js
#                               from elsewhere serves as well)
zs_packages=(cmake gcc g++ make pkg-config libpng-dev libjpeg62-turbo-dev check clang libcjson-dev
             libassimp-dev assimp-testmodels gnuplot-nox libosmesa6-dev valgrind chromium
             python3-pytest python3-numpy python3-venv python3-pip python3-setuptools
             python3-wheel emscripten dpkg-dev)

zs_missing=()
for p in "${zs_packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    zs_missing+=("$p")
  fi
done
command -v node >/dev/null || zs_missing+=(nodejs)
command -v npm >/dev/null || zs_missing+=(npm)
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
    [ "$t" = musl ] || [ "$t" = windows ] && continue # (their libraries: below)
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
  for t in "${zs_need[@]+"${zs_need[@]}"}"; do
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

# Debian's source packages PKG ... unpacked into DIR, through apt lists of
# our own (deb-src beside the machine's deb lines), so the machine's
# sources are left as they are: each at the newest version whose files
# the archive still serves (a security update's can be gone from a mirror).
zs_apt_source() {
  local dir=$1 apt p v ok
  shift
  apt=$(mktemp -d)
  mkdir -p "$apt/parts" "$apt/lists/partial"
  chmod 755 "$apt" "$dir" # (apt's download user writes there)
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] && sed 's/^Types: deb$/Types: deb-src/' "$f" >"$apt/parts/$(basename "$f")"
  done
  if [ -f /etc/apt/sources.list ]; then
    sed -n 's/^deb /deb-src /p' /etc/apt/sources.list >"$apt/parts/debian.list"
  fi
  local opts=(-o Dir::Etc::SourceList=/dev/null -o "Dir::Etc::SourceParts=$apt/parts"
              -o "Dir::State::Lists=$apt/lists")
  apt-get "${opts[@]}" update -qq >&2
  for p in "$@"; do
    ok=0
    for v in $(apt-cache "${opts[@]}" showsrc "$p" | sed -n 's/^Version: //p' | sort -u -r -V); do
      if (cd "$dir" && apt-get "${opts[@]}" source -qq "$p=$v") >/dev/null 2>&1; then
        ok=1
        break
      fi
    done
    if [ "$ok" -ne 1 ]; then
      echo "setup: cannot fetch the sources of $p" >&2
      rm -rf "$apt"
      return 1
    fi
  done
  rm -rf "$apt"
}

# cJSON's own sources for the teaching page's WebAssembly engine (Debian
# ships the library, not its sources).
zs_wasm_root=${ZS_WASM_ROOT:-/opt/zscan-wasm}
if [ ! -f "$zs_wasm_root/cjson/cJSON.c" ]; then
  if [ "$(id -u)" -ne 0 ] && [ ! -w "$(dirname "$zs_wasm_root")" ]; then
    echo "setup: $zs_wasm_root missing and not root: zscan teach will say so" >&2
  else
    echo "setup: cJSON's sources into $zs_wasm_root" >&2
    zs_src=$(mktemp -d)
    zs_apt_source "$zs_src" cjson
    rm -rf "$zs_wasm_root/cjson" "$zs_wasm_root/include" "$zs_wasm_root/cjson.part"
    mkdir -p "$zs_wasm_root/include/cjson"
    cp -r "$zs_src"/cjson-*/ "$zs_wasm_root/cjson.part"
    cp "$zs_wasm_root/cjson.part/cJSON.h" "$zs_wasm_root/include/cjson/"
    mv "$zs_wasm_root/cjson.part" "$zs_wasm_root/cjson" # whole, or not at all
    rm -rf "$zs_src"
  fi
fi

# libjpeg-turbo (its plain C path: its SIMD needs nasm, and gives the same
# texels), cJSON and check, static, from their Debian sources in $1 with
# the CMake arguments after it.
zs_build_cmake_libs() {
  local src=$1
  shift
  (cd "$src"/libjpeg-turbo-*/ &&
    cmake -S . -B zscan-build "$@" -DENABLE_SHARED=OFF -DWITH_SIMD=OFF -DWITH_TURBOJPEG=OFF &&
    cmake --build zscan-build -j "$(nproc)" --target install) &&
  (cd "$src"/cjson-*/ &&
    cmake -S . -B zscan-build "$@" -DBUILD_SHARED_LIBS=OFF -DENABLE_CJSON_TEST=OFF \
      -DENABLE_CJSON_UTILS=OFF &&
    cmake --build zscan-build -j "$(nproc)" --target install) &&
  (cd "$src"/check-*/ &&
    cmake -S . -B zscan-build "$@" -DBUILD_TESTING=OFF -DCHECK_ENABLE_SUBUNIT=OFF &&
    cmake --build zscan-build -j "$(nproc)" --target install)
}

# A static library set in $1 made whole: check installs a shared library
# too, named _pic in its .pc.
zs_static_only() {
  rm -f "$1"/lib/*.so* "$1"/lib/*.dll.a
  sed -i 's/-lcheck_pic/-lcheck/' "$1/lib/pkgconfig/check.pc"
  touch "$1/complete"
}

# The musl target of tools/cross-check.sh: musl-gcc, and the libraries
# zscan and its golden test link, built from Debian's sources as static
# libraries for musl into $ZS_MUSL_ROOT (Debian ships them for glibc
# only).
zs_musl_root=${ZS_MUSL_ROOT:-/opt/zscan-musl}
if [[ " ${ZS_CROSS:-} " == *" musl "* ]] && [ ! -f "$zs_musl_root/complete" ]; then
  if ! command -v musl-gcc >/dev/null; then
    export DEBIAN_FRONTEND=noninteractive
    apt-get install -y -qq --no-install-recommends musl-tools >&2
  fi
  echo "setup: the musl libraries into $zs_musl_root" >&2
  zs_src=$(mktemp -d)
  zs_apt_source "$zs_src" zlib libpng1.6 libjpeg-turbo cjson check
  rm -rf "$zs_musl_root"
  mkdir -p "$zs_musl_root"
  zs_m=$zs_musl_root
  zs_cmake_musl=(-DCMAKE_C_COMPILER=musl-gcc -DCMAKE_BUILD_TYPE=Release
                 "-DCMAKE_INSTALL_PREFIX=$zs_m" "-DCMAKE_INSTALL_LIBDIR=$zs_m/lib")
  if ! (
    set -e
    cd "$zs_src"/zlib-*/
    CC=musl-gcc CFLAGS=-O2 ./configure --static --prefix="$zs_m"
    make -j "$(nproc)" install
    cd "$zs_src"/libpng1.6-*/
    CC=musl-gcc CFLAGS=-O2 CPPFLAGS="-I$zs_m/include" LDFLAGS="-L$zs_m/lib" \
      ./configure --prefix="$zs_m" --disable-shared
    make -j "$(nproc)" install
    zs_build_cmake_libs "$zs_src" "${zs_cmake_musl[@]}"
  ) >"$zs_src/build.log" 2>&1; then
    tail -30 "$zs_src/build.log" >&2
    echo "setup: the musl libraries did not build" >&2
    exit 1
  fi
  zs_static_only "$zs_m"
  rm -rf "$zs_src"
fi

# The windows target of tools/cross-check.sh: mingw-w64 (its POSIX-threads
# flavour: winpthreads), wine to run what it builds, Debian's zlib for
# mingw-w64, and libpng, libjpeg-turbo, cJSON and check built from
# Debian's sources as static libraries into $ZS_WINDOWS_ROOT, beside the
# CMake toolchain file that builds them and zscan.
zs_windows_root=${ZS_WINDOWS_ROOT:-/opt/zscan-windows}
if [[ " ${ZS_CROSS:-} " == *" windows "* ]] && [ ! -f "$zs_windows_root/complete" ]; then
  zs_win_packages=(gcc-mingw-w64-x86-64-posix mingw-w64-x86-64-dev libz-mingw-w64-dev wine64)
  zs_missing_win=()
  for p in "${zs_win_packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
      zs_missing_win+=("$p")
  done
  if [ ${#zs_missing_win[@]} -gt 0 ]; then
    echo "setup: installing ${zs_missing_win[*]}" >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${zs_missing_win[@]}" >&2
  fi
  echo "setup: the windows libraries into $zs_windows_root" >&2
  zs_src=$(mktemp -d)
  zs_apt_source "$zs_src" libpng1.6 libjpeg-turbo cjson check
  rm -rf "$zs_windows_root"
  mkdir -p "$zs_windows_root"
  zs_w=$zs_windows_root
  cat >"$zs_w/toolchain.cmake" <<TOOLCHAIN
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(CMAKE_C_COMPILER x86_64-w64-mingw32-gcc-posix)
set(CMAKE_RC_COMPILER x86_64-w64-mingw32-windres)
set(CMAKE_CROSSCOMPILING_EMULATOR /usr/lib/wine/wine64)
set(CMAKE_FIND_ROOT_PATH $zs_w /usr/x86_64-w64-mingw32)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
TOOLCHAIN
  # (mingw-w64's own printf in them too, as in zscan: cJSON's numbers and
  # check's messages formatted as everywhere else)
  zs_cmake_win=(-DCMAKE_TOOLCHAIN_FILE="$zs_w/toolchain.cmake" -DCMAKE_BUILD_TYPE=Release
                -DCMAKE_C_FLAGS=-D__USE_MINGW_ANSI_STDIO=1
                "-DCMAKE_INSTALL_PREFIX=$zs_w" "-DCMAKE_INSTALL_LIBDIR=$zs_w/lib")
  if ! (
    set -e
    cd "$zs_src"/libpng1.6-*/
    cmake -S . -B zscan-build "${zs_cmake_win[@]}" -DPNG_SHARED=OFF -DPNG_TESTS=OFF -DPNG_EXECUTABLES=OFF
    cmake --build zscan-build -j "$(nproc)" --target install
    zs_build_cmake_libs "$zs_src" "${zs_cmake_win[@]}"
  ) >"$zs_src/build.log" 2>&1; then
    tail -30 "$zs_src/build.log" >&2
    echo "setup: the windows libraries did not build" >&2
    exit 1
  fi
  zs_static_only "$zs_w"
  rm -rf "$zs_src"
fi

# The browser tests' driver (tests/web/package.json: playwright-core, which
# drives Debian's chromium and downloads no browser), from the npm registry.
if [ ! -f "$zs_root/tests/web/node_modules/playwright-core/package.json" ]; then
  echo "setup: npm ci in tests/web" >&2
  (cd "$zs_root/tests/web" && npm ci --no-audit --no-fund --silent) >&2
fi

ZS_BUILD_DIR=${ZS_BUILD_DIR:-"$zs_root/build"}
ZS_BUILD_TYPE=${ZS_BUILD_TYPE:-Release}
# shellcheck disable=SC2086
cmake -S "$zs_root" -B "$ZS_BUILD_DIR" -DCMAKE_BUILD_TYPE="$ZS_BUILD_TYPE" \
  -DZS_WERROR=ON -DZS_WASM_ROOT="$zs_wasm_root" ${ZS_CMAKE_ARGS:-} >/dev/null
echo "setup: building in $ZS_BUILD_DIR" >&2
if ! cmake --build "$ZS_BUILD_DIR" -j "$(nproc)" >"$ZS_BUILD_DIR/build.log" 2>&1; then
  cat "$ZS_BUILD_DIR/build.log" >&2
  echo "setup: the build failed (log: $ZS_BUILD_DIR/build.log)" >&2
  exit 1
fi
