#!/usr/bin/env bash
# Installs the build in $ZS_BUILD_DIR (default build/) into a temporary
# prefix and builds examples/ against it three ways, as users would:
# find_package(zscan), `cc ... $(pkg-config --cflags --libs zscan)`, and
# zscan's source tree as a subproject (add_subdirectory).  Each
# render_hash must print the image_hash of `zscan render`.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ZS_BUILD_DIR:-$root/build}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"

cmake --install "$build" --prefix "$prefix" >/dev/null
for f in lib/libzscan.so.0 lib/libzscan.a include/zscan/zscan.h lib/pkgconfig/zscan.pc \
         lib/cmake/zscan/zscanConfig.cmake bin/zscan; do
  [ -e "$prefix/$f" ] || { echo "check-package: $f was not installed" >&2; exit 1; }
done
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
version=$(pkg-config --modversion zscan)
"$prefix/bin/zscan" --version | head -1 | grep -qx "zscan $version (library $version)" ||
  { echo "check-package: pkg-config says $version, zscan --version says otherwise" >&2; exit 1; }

input="$root/tests/data/scenes/cyclic.obj"
want=$("$prefix/bin/zscan" render "$input" --size 160x120 --stats -o "$work/cli.png" |
       sed 's/.*"image_hash":"\([0-9a-f]*\)".*/\1/')
check() { # NAME HASH
  if [ "$2" != "$want" ]; then
    echo "check-package: $1 printed $2, zscan render $want" >&2
    exit 1
  fi
  echo "check-package: $1: $2, as zscan render"
}

# 1. find_package(zscan) against the prefix (C and C++)
cmake -S "$root/examples" -B "$work/find" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/find" -j "$(nproc)" >/dev/null
check "find_package render_hash" "$("$work/find/render_hash" "$input" 160 120 | tail -1)"
"$work/find/query_mesh" | grep -q "box behind the wall: 0 samples"

# 2. pkg-config and nothing else
cc -std=c11 -Wall -Wextra -Werror "$root/examples/render_hash.c" \
  $(pkg-config --cflags --libs zscan) -o "$work/render_hash_pc"
check "pkg-config render_hash" "$(LD_LIBRARY_PATH="$prefix/lib" "$work/render_hash_pc" "$input" 160 120 | tail -1)"

# 3. zscan's source tree as a subproject
cmake -S "$root/examples" -B "$work/sub" -DZSCAN_SOURCE_DIR="$root" >/dev/null
cmake --build "$work/sub" -j "$(nproc)" >/dev/null
check "add_subdirectory render_hash" "$("$work/sub/render_hash" "$input" 160 120 | tail -1)"
echo "check-package: 3 passed, 0 failed"
