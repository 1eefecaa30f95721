#!/usr/bin/env bash
# The Python package as a user installs it: a wheel built offline from this
# checkout (pip with Debian's setuptools and wheel, no build isolation, no
# index), libzscan built by CMake inside it, installed into a fresh virtual
# environment (with the system's site-packages, where Debian's numpy and
# pytest are), then the binding's tests run against the installed package
# with no checkout on its path and no ZSCAN_LIBRARY.
#   tools/check-wheel.sh [BUILD_DIR]   BUILD_DIR's zscan command is what the
#                                      tests compare with (default: build/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
[ -x "$build/zscan" ] || { echo "check-wheel: no zscan command in $build" >&2; exit 1; }
py=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# pip builds in the directory it is given: a copy, so the checkout stays clean
cp -r "$root/python" "$work/src"
rm -rf "$work/src/build" "$work/src/zscan.egg-info" "$work/src/zscan/libzscan.so"*
"$py" -m venv --system-site-packages "$work/venv"
echo "check-wheel: building the wheel (libzscan with CMake) and installing it"
ZSCAN_SOURCE_DIR=$root "$work/venv/bin/python" -m pip wheel --no-build-isolation --no-index \
  --no-deps -w "$work/dist" "$work/src" >"$work/pip.log" 2>&1 || { cat "$work/pip.log" >&2; exit 1; }
wheel=$(ls "$work/dist"/zscan-*.whl)
echo "check-wheel: $(basename "$wheel")"
"$work/venv/bin/python" -m pip install --no-index --no-deps "$wheel" >"$work/pip.log" 2>&1 ||
  { cat "$work/pip.log" >&2; exit 1; }
cd "$work"
env -u ZSCAN_LIBRARY -u PYTHONPATH ZSCAN_TEST_INSTALLED=1 ZSCAN_BUILD_DIR="$build" \
  PYTHONDONTWRITEBYTECODE=1 "$work/venv/bin/python" -m pytest -q -p no:cacheprovider \
  "$root/python/tests"
