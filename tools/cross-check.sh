#!/usr/bin/env bash
# The same bytes on other CPUs: for each target (aarch64, s390x with its
# big-endian words, i686 with SSE2 arithmetic), zscan and its golden test
# cross-built with Debian's cross compiler against the target's own
# libraries (tools/setup.sh unpacks them, ZS_CROSS), then run under
# qemu-user (aarch64 with its NEON span fill): every golden image's hash
# must be tests/golden/hashes.txt's,
# and every counter, modelled time and image hash `zscan render --stats`
# and `zscan walk --csv` print for a set of scenes, modes, shadings and
# culling methods must be the native build's, byte for byte (their wall
# times aside, and on i686 the memory sizes, which a 32-bit device's
# pointers make its own).  Models of assimp's formats are left to the native tests.
#
# musl (x86-64 with musl's C library) is built against libraries
# tools/setup.sh builds from Debian's sources, and run as it is; windows
# (x86-64) with mingw-w64 against such libraries, and run under wine,
# where the outputs' guarantees are tried too (a file replaced whole, one
# kept on an error, no temporary left, a missing folder and a directory
# refused, with a separator after it too, standard output's bytes as they
# are, the null device, a page gathered in memory, a UTF-8 file name).
#
#   tools/cross-check.sh [TARGET ...]     (default: aarch64 s390x i686 musl windows)
#
# Environment: ZS_CROSS_ROOT (as tools/setup.sh), ZS_BUILD_DIR (the
# native build, default build/), ZS_CROSS_BUILD (default build-cross).
set -euo pipefail

zs_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=tools/cross-targets.sh
. "$zs_root/tools/cross-targets.sh"
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(aarch64 s390x i686 musl windows)
for t in "${targets[@]}"; do zs_cross_target "$t" >/dev/null || exit 2; done
ZS_CROSS="${targets[*]}" "$zs_root/tools/setup.sh"
source_root=${ZS_CROSS_ROOT:-/opt/zscan-cross}
native=${ZS_BUILD_DIR:-"$zs_root/build"}/zscan
out=${ZS_CROSS_BUILD:-"$zs_root/build-cross"}
mkdir -p "$out"

# The cases: what a renderer's user compares, through every mode and
# style, the shadings that read attributes, shadows, samples, transparency
# and the culling methods; and a walk with moving objects.
renders=(
  "builtin:default --algo zbuffer"         "builtin:default --algo scanline"
  "builtin:default --algo depthsort"       "builtin:default --shade id"
  "builtin:default --shade depth"          "builtin:default --style hidden-line"
  "builtin:default --shade phong --shadows" "builtin:default --samples 4"
  "builtin:cubes,n=4 --cull chc"           "builtin:cubes,n=4 --cull hzb --shade id"
  "builtin:teapots,count=60 --cull chcpp"  "builtin:teapots,count=60 --algo depthsort"
  "builtin:spheres,count=200 --shade gouraud" "builtin:city --cull nohc"
  "builtin:plant,detail=0.1 --algo scanline" "builtin:plant,detail=0.1 --cull chc-prob"
  "scene/examples/glass.json"              "scene/examples/glass.json --algo scanline --samples 2"
  "scene/examples/spotlight.json"          "scene/examples/teapot_textured.json --shade gouraud"
)
walk="builtin:teapots,count=80,moving=20 --cull chc,chcpp,hzb --frames 12 --algos scanline,depthsort"

# Every line the cases print, wall times dropped; $1 runs zscan.
run_cases() {
  local zscan=$1 i=0
  for r in "${renders[@]}"; do
    # shellcheck disable=SC2086
    (cd "$zs_root" && $zscan render $r --size 200x150 -o "$out/case-$i.png" --stats -q) |
      sed 's/,"timing":{[^}]*}//'
    i=$((i + 1))
  done
  # shellcheck disable=SC2086
  (cd "$zs_root" && $zscan walk $walk --size 160x120 --csv "$out/walk.csv" --quiet >/dev/null)
  cut -d, -f1-5,7- "$out/walk.csv"
}

run_cases "$native" >"$out/native.txt"
status=0
# The musl build: x86-64 with musl's C library (musl-gcc) against the
# static libraries tools/setup.sh built for it, run as it is.
build_musl() {
  local m=${ZS_MUSL_ROOT:-/opt/zscan-musl}
  echo "cross-check: musl: building" >&2
  PKG_CONFIG_LIBDIR="$m/lib/pkgconfig" \
    cmake -S "$zs_root" -B "$build" -DCMAKE_C_COMPILER=musl-gcc -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_C_STANDARD_LIBRARIES="-L$m/lib -lz -lm -lpthread" -DZS_WERROR=ON -DZS_ASSIMP=OFF \
    -DZS_MESA=OFF -DZS_TEACH_WASM=OFF >"$build/configure.log" 2>&1 ||
    { cat "$build/configure.log" >&2; exit 1; }
  cmake --build "$build" -j "$(nproc)" --target zscan test_golden >"$build/build.log" 2>&1 ||
    { cat "$build/build.log" >&2; exit 1; }
}

# The suites that also run under wine as they are (beside the golden
# one); the others fork, make FIFOs, sockets or links, capture standard
# output inside the process, or run the host's valgrind and gnuplot.
wine_suites=(test_cull test_depthsort test_exactmath test_generate test_hzb test_lines test_obj
             test_octree test_os test_prims test_query test_raster test_samples test_shadow
             test_stress test_surface test_teach test_teapot test_transparency)

# The windows build: mingw-w64 with the toolchain file and static
# libraries tools/setup.sh made, run under wine in a prefix of its own.
build_windows() {
  local w=${ZS_WINDOWS_ROOT:-/opt/zscan-windows}
  echo "cross-check: windows: building" >&2
  PKG_CONFIG_LIBDIR="$w/lib/pkgconfig:/usr/x86_64-w64-mingw32/lib/pkgconfig" \
    cmake -S "$zs_root" -B "$build" -DCMAKE_TOOLCHAIN_FILE="$w/toolchain.cmake" \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXE_LINKER_FLAGS=-static \
    -DCMAKE_C_STANDARD_LIBRARIES="-lz -lssp" -DZS_WERROR=ON -DZS_ASSIMP=OFF -DZS_MESA=OFF \
    -DZS_TEACH_WASM=OFF >"$build/configure.log" 2>&1 ||
    { cat "$build/configure.log" >&2; exit 1; }
  cmake --build "$build" -j "$(nproc)" --target zscan test_golden "${wine_suites[@]}" \
    >"$build/build.log" 2>&1 || { cat "$build/build.log" >&2; exit 1; }
  export WINEPREFIX="$build/wine" WINEDEBUG=-all
  /usr/lib/wine/wine64 wineboot --init >/dev/null 2>&1 || true
  run=/usr/lib/wine/wine64
  exe=.exe
}

# The output primitive's promises, tried with Windows' own calls: $1 runs
# zscan; prints what broke, nothing when all held.
check_outputs() {
  local zscan=$1 d="$build/outputs" good
  rm -rf "$d"
  mkdir -p "$d/dir"
  good="$d/native.png"
  "$native" render builtin:default --size 200x150 -o "$good" -q
  printf 'old' >"$d/kept.png"
  # shellcheck disable=SC2086
  if $zscan render no-such-scene.obj -o "$d/kept.png" -q 2>/dev/null ||
    [ "$(cat "$d/kept.png")" != old ]; then
    echo "a failed render changed the file it was to write"
  fi
  # shellcheck disable=SC2086
  $zscan render builtin:default --size 200x150 -o "$d/kept.png" -q 2>"$d/err.txt" &&
    cmp -s "$d/kept.png" "$good" || echo "a file was not replaced by the image: $(cat "$d/err.txt")"
  # shellcheck disable=SC2086
  $zscan render builtin:default --size 200x150 -o - -q >"$d/stdout.png" 2>"$d/err.txt" &&
    cmp -s "$d/stdout.png" "$good" || echo "standard output's PNG differs: $(cat "$d/err.txt")"
  # shellcheck disable=SC2086
  $zscan render builtin:default -o "$d/missing/x.png" -q 2>"$d/err.txt" &&
    echo "a missing folder was written into"
  grep -q "no such directory" "$d/err.txt" || echo "a missing folder's message: $(cat "$d/err.txt")"
  # shellcheck disable=SC2086
  $zscan render builtin:default -o "$d/dir" -q 2>"$d/err.txt" && echo "a directory was written"
  grep -q "is a directory" "$d/err.txt" || echo "a directory's message: $(cat "$d/err.txt")"
  # shellcheck disable=SC2086
  $zscan render builtin:default -o NUL -q 2>"$d/err.txt" ||
    echo "the null device was not written: $(cat "$d/err.txt")"
  # shellcheck disable=SC2086
  $zscan render builtin:default -o "$d/dir\\" -q 2>"$d/err.txt" && echo "a directory\\ was written"
  grep -q "is a directory" "$d/err.txt" || echo "a directory\\'s message: $(cat "$d/err.txt")"
  # shellcheck disable=SC2086
  $zscan trace builtin:default --size 16x12 --html "$d/trace.html" >/dev/null 2>"$d/err.txt" &&
    "$native" trace builtin:default --size 16x12 --html "$d/native.html" >/dev/null &&
    cmp -s "$d/trace.html" "$d/native.html" || echo "the trace's page differs: $(cat "$d/err.txt")"
  # shellcheck disable=SC2086
  $zscan render builtin:default --size 200x150 -o "$d/čaj-テスト.png" -q 2>"$d/err.txt" &&
    cmp -s "$d/čaj-テスト.png" "$good" || echo "a UTF-8 name was not written: $(cat "$d/err.txt")"
  ls "$d" "$d/dir" | grep -q "\.tmp\." && echo "a temporary was left: $(ls "$d")"
  return 0
}

# A Debian cross target: its toolchain file, the build, and how to run it
# (qemu-user; i686 on this CPU where it can), in run.
build_cross() {
  cat >"$build/toolchain.cmake" <<TOOLCHAIN
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR $t)
set(CMAKE_C_COMPILER $triplet-gcc)
set(CMAKE_CXX_COMPILER $triplet-g++)
set(CMAKE_CROSSCOMPILING_EMULATOR $qemu)
set(CMAKE_FIND_ROOT_PATH $root /usr/$triplet)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_C_FLAGS_INIT "-isystem $root/usr/include/$multiarch")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,-rpath-link,$root/lib/$multiarch -Wl,-rpath-link,$root/usr/lib/$multiarch")
set(CMAKE_SHARED_LINKER_FLAGS_INIT "\${CMAKE_EXE_LINKER_FLAGS_INIT}")
TOOLCHAIN
  echo "cross-check: $t: building" >&2
  PKG_CONFIG_LIBDIR="$root/usr/lib/$multiarch/pkgconfig:$root/usr/share/pkgconfig" \
    PKG_CONFIG_SYSROOT_DIR="$root" \
    cmake -S "$zs_root" -B "$build" -DCMAKE_TOOLCHAIN_FILE="$build/toolchain.cmake" \
    -DCMAKE_BUILD_TYPE=Release -DZS_WERROR=ON -DZS_ASSIMP=OFF >"$build/configure.log" 2>&1 ||
    { cat "$build/configure.log" >&2; exit 1; }
  cmake --build "$build" -j "$(nproc)" --target zscan test_golden >"$build/build.log" 2>&1 ||
    { cat "$build/build.log" >&2; exit 1; }
  export QEMU_LD_PREFIX="/usr/$triplet"
  export LD_LIBRARY_PATH="$root/usr/lib/$multiarch:$root/lib/$multiarch"
  # i686 runs on this CPU itself where the kernel runs 32-bit programs
  # (through the cross libc's loader: a real SSE2 unit, and many times
  # faster than emulated), else under qemu like the others
  run="$qemu"
  if [ "$t" = i686 ]; then
    loader="/usr/$triplet/lib/ld-linux.so.2 --library-path $LD_LIBRARY_PATH:/usr/$triplet/lib"
    # shellcheck disable=SC2086
    if $loader "$build/zscan" --version >/dev/null 2>&1; then run=$loader; fi
  fi
}

for t in "${targets[@]}"; do
  read -r _ triplet qemu multiarch <<<"$(zs_cross_target "$t")"
  root="$source_root/$t"
  build="$out/$t"
  rm -rf "$build" # the toolchain's flags take at a first configure only
  mkdir -p "$build"
  exe=""
  if [ "$t" = musl ]; then
    build_musl
    run=""
  elif [ "$t" = windows ]; then
    build_windows
  else
    build_cross
  fi
  # aarch64 fills its spans with NEON: the comparisons below are of that path
  # shellcheck disable=SC2086
  fill=$($run "$build/zscan$exe" --version | sed -n 's/^span fill: //p')
  echo "cross-check: $t: span fill $fill" >&2
  if [ "$t" = aarch64 ] && [ "$fill" != neon ]; then
    echo "cross-check: aarch64: the span fill is '$fill', not neon" >&2
    status=1
  fi
  # the golden suite everywhere; under wine the others that run there too
  suites=(test_golden)
  [ "$t" = windows ] && suites+=("${wine_suites[@]}")
  more=""
  [ ${#suites[@]} -gt 1 ] && more=" and $((${#suites[@]} - 1)) more suites"
  echo "cross-check: $t: the golden images$more (${run:-natively})" >&2
  for suite in "${suites[@]}"; do
    # shellcheck disable=SC2086
    if ! (cd "$build" && CK_DEFAULT_TIMEOUT=0 $run "./$suite$exe" >"$suite.log" 2>&1); then
      grep -v "skipped$" "$build/$suite.log" >&2
      echo "cross-check: $t: $suite failed (above)" >&2
      status=1
    fi
  done
  echo "cross-check: $t: ${#renders[@]} renders and a walk against the native build" >&2
  run_cases "$run $build/zscan$exe" >"$build/cases.txt"
  want="$out/native.txt"
  if [ "$t" = i686 ]; then
    # the memory a 32-bit device holds is its own (pointers of 4 bytes)
    bytes='s/"\(buffer\|table\|vertex\)_bytes":[0-9]*,//g'
    sed "$bytes" "$out/native.txt" >"$build/native.txt"
    sed -i "$bytes" "$build/cases.txt"
    want="$build/native.txt"
  fi
  if ! diff "$want" "$build/cases.txt" >"$build/cases.diff"; then
    head -20 "$build/cases.diff" >&2
    echo "cross-check: $t: the outputs differ from the native build's ($build/cases.diff)" >&2
    status=1
  else
    echo "cross-check: $t: $(grep -c . "$want") lines, every one the native build's" >&2
  fi
  if [ "$t" = windows ]; then
    broken=$(check_outputs "$run $build/zscan$exe")
    if [ -n "$broken" ]; then
      echo "$broken" >&2
      echo "cross-check: windows: the outputs' guarantees do not hold (above)" >&2
      status=1
    else
      echo "cross-check: windows: outputs replaced whole, kept on an error, refused where they must be" >&2
    fi
  fi
  unset QEMU_LD_PREFIX LD_LIBRARY_PATH WINEPREFIX WINEDEBUG
done
exit $status
