#!/usr/bin/env bash
# Quick start, step 2: set up, build, and run every test (ctest over the
# check suites).  Exits non-zero on any failure.  Extra arguments go to
# ctest (e.g. -R golden).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/setup.sh"
cd "${ZS_BUILD_DIR:-$root/build}"
ctest --output-on-failure -j "$(nproc)" "$@"
