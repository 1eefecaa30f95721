#!/usr/bin/env bash
# Quick start, step 1: set up, build (Release), render the embedded default
# scene to zscan.png and print the frame's statistics.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/setup.sh"
"${ZS_BUILD_DIR:-$root/build}/zscan" render -o zscan.png --stats "$@"
echo "wrote zscan.png" >&2
