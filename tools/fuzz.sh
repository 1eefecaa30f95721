#!/usr/bin/env bash
# Fuzz every target of tests/fuzz/ with libFuzzer for SECONDS each (default
# 60), under AddressSanitizer and UndefinedBehaviorSanitizer.  The corpora
# start from the test inputs (OBJ files for the OBJ reader, the render and
# the culling methods, scene files for the scene reader, lessons for the
# teaching page's engine) and grow in
# $ZS_FUZZ_DIR (default build-fuzz/corpus).  A crash stops the run with
# the input saved as crash-* in the current directory and a non-zero exit.
#   tools/fuzz.sh          a minute per target (what CI runs)
#   tools/fuzz.sh 600      ten minutes per target
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
build=${ZS_FUZZ_BUILD:-"$root/build-fuzz"}
corpus=${ZS_FUZZ_DIR:-"$build/corpus"}
CC=clang cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DZS_FUZZ=ON \
  -DZS_SANITIZE=ON -DZS_TESTS=OFF -DZS_WERROR=ON >/dev/null
if ! cmake --build "$build" -j "$(nproc)" --target fuzz_obj fuzz_scene fuzz_render fuzz_cull fuzz_teach \
  >"$build/build.log" 2>&1; then
  cat "$build/build.log" >&2
  exit 1
fi
mkdir -p "$corpus/obj" "$corpus/scene" "$corpus/render" "$corpus/cull" "$corpus/teach"
cp "$root"/tests/data/*/*.obj "$corpus/obj/"
cp "$root"/tests/data/*/*.obj "$corpus/render/"
cp "$root"/tests/data/*/*.obj "$corpus/cull/"
cp "$root"/scene/examples/*.json "$root"/tests/data/bad_scene/*.json "$corpus/scene/"
cp "$root"/tests/data/lessons/*.json "$corpus/teach/"
# (the status is the fuzzer's own: under pipefail, "| grep ... || true"
# would turn a crash into success)
for t in obj scene render cull teach; do
  echo "fuzz_$t: $seconds s"
  status=0
  "$build/fuzz_$t" "$corpus/$t" -seed=1 -max_total_time="$seconds" -max_len=8192 \
    -print_final_stats=1 >"$build/fuzz_$t.log" 2>&1 || status=$?
  grep -E "^stat::number_of_executed_units|DONE|ERROR|SUMMARY|differs" "$build/fuzz_$t.log" || true
  if [ "$status" -ne 0 ]; then
    echo "fuzz_$t failed (exit $status); its log: $build/fuzz_$t.log" >&2
    exit 1
  fi
done
