#!/bin/sh
# Runs the Python binding's tests against one build of zscan:
#   python/run-tests.sh BUILD_DIR [pytest options...]
# BUILD_DIR holds libzscan.so and the zscan command (default: build/ of this
# checkout).  The Python is $PYTHON if set, else the first of python3 and
# /usr/bin/python3 that has pytest (Debian's python3-pytest installs it for
# /usr/bin/python3, which another python3 on PATH may not see).
# Exit status: pytest's, except that "no tests ran" (5) is a failure too.
set -u
here=$(cd "$(dirname "$0")" && pwd)
src=$(dirname "$here")
build=${1:-$src/build}
[ $# -gt 0 ] && shift
given=$build
build=$(cd "$given" 2>/dev/null && pwd) || { echo "run-tests.sh: no build directory '$given'" >&2; exit 1; }
if [ ! -e "$build/libzscan.so" ] || [ ! -x "$build/zscan" ]; then
  echo "run-tests.sh: $build has no libzscan.so or zscan: build the zscan_shared and zscan targets" >&2
  exit 1
fi

py=${PYTHON:-}
if [ -z "$py" ]; then
  for p in python3 /usr/bin/python3; do
    if command -v "$p" >/dev/null 2>&1 && "$p" -c 'import pytest' >/dev/null 2>&1; then
      py=$p
      break
    fi
  done
fi
if [ -z "$py" ]; then
  echo "run-tests.sh: no python3 with pytest (Debian: apt-get install python3-pytest python3-numpy)" >&2
  exit 1
fi
if ! "$py" -c 'import numpy' >/dev/null 2>&1; then
  echo "run-tests.sh: $py has no numpy, which meshes from arrays need (Debian: apt-get install python3-numpy)" >&2
  exit 1
fi

ZSCAN_LIBRARY=$build/libzscan.so
ZSCAN_BUILD_DIR=$build
PYTHONPATH=$here${PYTHONPATH:+:$PYTHONPATH}
# nothing written into the source tree: no __pycache__, no .pytest_cache
PYTHONDONTWRITEBYTECODE=1
export ZSCAN_LIBRARY ZSCAN_BUILD_DIR PYTHONPATH PYTHONDONTWRITEBYTECODE

cd "$src" || exit 1
"$py" -m pytest -q -p no:cacheprovider "$here/tests" "$@"
rc=$?
if [ "$rc" -eq 5 ]; then
  echo "run-tests.sh: pytest collected no tests" >&2
  exit 1
fi
exit "$rc"
