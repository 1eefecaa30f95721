#!/usr/bin/env bash
# Fuzz every target of tests/fuzz/ with libFuzzer for SECONDS each (default
# 60), under AddressSanitizer and UndefinedBehaviorSanitizer.  The corpora
# start from the test inputs (OBJ files for the OBJ reader, the render and
# the culling methods, scene files for the scene reader, lessons for the
# teaching page's engine, images for the texture decoders) and grow in
# $ZS_FUZZ_DIR (default build-fuzz/corpus).  A crash stops the run with
# the input saved as crash-* in the current directory and a non-zero exit.
#   tools/fuzz.sh          a minute per target (what CI runs)
#   tools/fuzz.sh 600      ten minutes per target
#   ZS_FUZZ_ASSIMP=1 tools/fuzz.sh   also fuzz_assimp, the models read
#                          through assimp (not in CI: assimp's own readers
#                          fail under it; tests/fuzz/fuzz_assimp.c says how)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
build=${ZS_FUZZ_BUILD:-"$root/build-fuzz"}
corpus=${ZS_FUZZ_DIR:-"$build/corpus"}
CC=clang cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DZS_FUZZ=ON \
  -DZS_SANITIZE=ON -DZS_TESTS=OFF -DZS_WERROR=ON >/dev/null
targets="obj scene render cull teach texture"
if [ "${ZS_FUZZ_ASSIMP:-0}" = 1 ]; then targets="$targets assimp"; fi
if ! cmake --build "$build" -j "$(nproc)" --target $(printf 'fuzz_%s ' $targets) \
  >"$build/build.log" 2>&1; then
  cat "$build/build.log" >&2
  exit 1
fi
for t in $targets; do mkdir -p "$corpus/$t"; done
cp "$root"/tests/data/*/*.obj "$corpus/obj/"
cp "$root"/tests/data/*/*.obj "$corpus/render/"
cp "$root"/tests/data/*/*.obj "$corpus/cull/"
cp "$root"/scene/examples/*.json "$root"/tests/data/bad_scene/*.json "$corpus/scene/"
cp "$root"/tests/data/lessons/*.json "$corpus/teach/"
cp "$root"/tests/data/textures/*.png "$root"/tests/data/textures/*.jpg \
  "$root"/scene/examples/checker/checker.png "$corpus/texture/"
if [ -d "$corpus/assimp" ]; then
  # each model behind its format's byte (fuzz_assimp.c: ply 0, gltf 1, off 2, stl 3)
  for f in "$root"/tests/data/models/* "$root"/tests/data/bad_models/*; do
    case $f in *.ply) b=0 ;; *.gltf) b=1 ;; *.off) b=2 ;; *.stl) b=3 ;; *) continue ;; esac
    { printf "\\$(printf %03o "$b")"; head -c 8191 "$f"; } >"$corpus/assimp/$(basename "$f")"
  done
  export LSAN_OPTIONS="suppressions=$root/tests/fuzz/assimp.supp"
fi
# (the status is the fuzzer's own: under pipefail, "| grep ... || true"
# would turn a crash into success)
for t in $targets; do
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
