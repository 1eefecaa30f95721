#!/usr/bin/env bash
# Two builds of zscan timed in turn: whether a change made a frame slower.
#
#   tools/bench-builds.sh [options] BASE [NEW]
#
# BASE and NEW (default HEAD) are git revisions of this checkout; each is
# exported into a folder of its own under a temporary directory and built
# the same way (Release, the compiler CMake finds).  Then both run
#   zscan bench raster --algo zbuffer --threads 1 [--shade S]
# in turn, ROUNDS times each; a case's figure is the least of its medians
# over the rounds (the run the machine disturbed least), and the table
# gives NEW / BASE for each case both builds bench, and their geometric mean.
#
#   --before TEXT  BASE is the commit before the oldest one whose subject
#                  begins with TEXT (a change named by its message)
#   --change TEXT  BASE that commit's parent and NEW the commit: what the
#                  one change cost
#   --shade S      bench raster's shading (default flat, asked for by no
#                  option, which builds before the shadings lack)
#   --rounds K     runs of each build (default 5)
#   --repeat N     bench raster's frames a case (default 11)
#   --md FILE      the table in Markdown, with the command that made it
#
# Exit 2 for a usage error, 1 when a revision is unknown or fails to build.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

usage() {
  sed -n '3,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2
  exit 2
}

shade=flat rounds=5 repeat=11 md= before= change=0 revs=()
args=("$@")
while [ $# -gt 0 ]; do
  case "$1" in
    --before) [ $# -ge 2 ] || usage; before=$2; shift 2 ;;
    --change) [ $# -ge 2 ] || usage; before=$2; change=1; shift 2 ;;
    --shade) [ $# -ge 2 ] || usage; shade=$2; shift 2 ;;
    --rounds) [ $# -ge 2 ] || usage; rounds=$2; shift 2 ;;
    --repeat) [ $# -ge 2 ] || usage; repeat=$2; shift 2 ;;
    --md) [ $# -ge 2 ] || usage; md=$2; shift 2 ;;
    -h|--help) usage ;;
    -*) echo "bench-builds.sh: $1: unknown option" >&2; exit 2 ;;
    *) revs+=("$1"); shift ;;
  esac
done
case "$rounds$repeat" in *[!0-9]*|'') echo "bench-builds.sh: --rounds and --repeat take a count" >&2; exit 2 ;; esac
if [ -n "$before" ]; then
  [ ${#revs[@]} -le $((1 - change)) ] || usage
  first=$(git -C "$root" log --reverse --format='%H %s' | awk -v t="$before" \
    '!found && index(substr($0, 42), t) == 1 { print $1; found = 1 }')
  [ -n "$first" ] || { echo "bench-builds.sh: no commit's subject begins with '$before'" >&2; exit 1; }
  if [ $change = 1 ]; then
    revs=("$first^" "$first")
  else
    revs=("$first^" ${revs[@]+"${revs[@]}"})
  fi
fi
[ ${#revs[@]} -ge 1 ] && [ ${#revs[@]} -le 2 ] || usage
base=${revs[0]} new=${revs[1]:-HEAD}
shade_opt=()
[ "$shade" = flat ] || shade_opt=(--shade "$shade")

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

build() { # revision, folder
  local rev=$1 dir=$2
  git -C "$root" rev-parse --verify --quiet "$rev^{commit}" >/dev/null ||
    { echo "bench-builds.sh: $rev: not a revision of $root" >&2; exit 1; }
  mkdir -p "$dir/src"
  git -C "$root" archive "$rev" | tar -x -C "$dir/src"
  echo "building $rev ..." >&2
  if ! { cmake -S "$dir/src" -B "$dir/build" -DCMAKE_BUILD_TYPE=Release >"$dir/build.log" 2>&1 &&
         cmake --build "$dir/build" -j"$(nproc)" --target zscan >>"$dir/build.log" 2>&1; }; then
    tail -20 "$dir/build.log" >&2
    echo "bench-builds.sh: $rev: the build failed ($dir/build.log above)" >&2
    exit 1
  fi
}
build "$base" "$tmp/base"
build "$new" "$tmp/new"

# A round: each build's bench raster once, the two in turn, from the new
# build's tree (the scene files a case names are there).
for r in $(seq "$rounds"); do
  for b in base new; do
    (cd "$tmp/new/src" && "$tmp/$b/build/zscan" bench raster --algo zbuffer \
       --threads 1 ${shade_opt[@]+"${shade_opt[@]}"} --repeat "$repeat" --csv "$tmp/$b.$r.csv" >/dev/null)
  done
  echo "round $r of $rounds" >&2
done

# A case's name may hold commas (builtin:default,level=42): the columns
# are counted from the end of the row, where the header's names hold none.
table=$(awk -F, -v rounds="$rounds" '
  FNR == 1 { for (i = 1; i <= NF; i++) if ($i == "ms") from_end = NF - i; H = NF
             b = FILENAME; sub(/.*\//, "", b); sub(/\..*/, "", b); next }
  { name = $1; for (i = 2; i <= NF - H + 1; i++) name = name "," $i
    ms = $(NF - from_end)
    if (!(name in seen)) { seen[name] = 1; order[++n] = name }
    key = b SUBSEP name
    if (!(key in best) || ms + 0 < best[key]) best[key] = ms + 0 }
  END { print "| case | before ms | after ms | after / before |"
        print "|---|---|---|---|"
        for (k = 1; k <= n; k++) {
          c = order[k]
          if (!(("base" SUBSEP c) in best) || !(("new" SUBSEP c) in best)) continue
          r = best["new" SUBSEP c] / best["base" SUBSEP c]
          printf "| `%s` | %.3f | %.3f | %.3f |\n", c, best["base" SUBSEP c], best["new" SUBSEP c], r
          logsum += log(r); cases++ }
        if (cases) printf "| every case (the geometric mean) | | | %.3f |\n", exp(logsum / cases) }' \
  $(for r in $(seq "$rounds"); do echo "$tmp/base.$r.csv" "$tmp/new.$r.csv"; done))

# the command as it measured, without where it wrote
shown=() skip=0
for a in "${args[@]}"; do
  if [ $skip = 1 ]; then skip=0; continue; fi
  if [ "$a" = --md ]; then skip=1; continue; fi
  shown+=("$a")
done
quoted=
for a in ${shown[@]+"${shown[@]}"}; do
  if [[ $a =~ ^[A-Za-z0-9_./:=,+^-]+$ ]]; then quoted+=" $a"; else quoted+=" \"$a\""; fi
done
echo "$table"
if [ -n "$md" ]; then
  {
    echo "\`tools/bench-builds.sh$quoted\`:"
    echo
    echo "$table"
  } >"$md.tmp" && mv "$md.tmp" "$md"
  echo "wrote $md" >&2
fi
