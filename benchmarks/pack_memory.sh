#!/usr/bin/env bash
# Peak memory and wall time of `mocapdb pack` on the two shared folders, and on a collection COPIES
# times their size (issue 14, acceptance 4: packing memory grows with the largest group, not with
# the file). The copies are the same clips made distinct files (a comment line in each AMC, a blank
# line after each BVH) so that import stores them as new clips under ids suffixed -2, -3, ...
#
# Usage: benchmarks/pack_memory.sh [BUILD_DIR=build/release] [WORK_DIR=/tmp/mocapdb-pack-memory] [COPIES=10] [E=1]
# Needs /usr/bin/time (Debian package time) and about 400 MB of disk per copy in WORK_DIR.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
work=${2:-/tmp/mocapdb-pack-memory}
copies=${3:-10}
E=${4:-1}
cli="$build/tools/mocapdb"
amc=../shared/datasets/cmu-asfamc
bvh=../shared/datasets/cmu-walkrun-pfnn
[ -x "$cli" ] || { echo "pack_memory.sh: no $cli (build first)" >&2; exit 2; }
[ -d "$amc" ] && [ -d "$bvh" ] || { echo "pack_memory.sh: ../shared/datasets not found" >&2; exit 2; }
rm -rf "$work"
mkdir -p "$work"

make_copy() {  # $1 = copy index: the folders' files, each made a distinct file
  local dir="$work/copies/$1"
  mkdir -p "$dir/amc" "$dir/bvh"
  cp "$amc"/*.asf "$dir/amc/"
  for f in "$amc"/*.amc; do { echo "# copy $1"; cat "$f"; } > "$dir/amc/$(basename "$f")"; done
  for f in "$bvh"/*.bvh; do { cat "$f"; for _ in $(seq "$1"); do echo; done; } > "$dir/bvh/$(basename "$f")"; done
}

import() {  # $1 = database, then folders (copies of amc/ and bvh/)
  local db=$1; shift
  local d
  for d in "$@"; do
    if [ "$(basename "$d")" = bvh ]; then "$cli" import "$d" --fps 60 -o "$db" >/dev/null
    else "$cli" import "$d" -o "$db" >/dev/null; fi
  done
}

measure() {  # $1 = label, $2 = database
  local json out
  out=$( { /usr/bin/time -f "TIME %e %M" "$cli" pack "$2" --max-error-cm "$E" --json >"$work/pack.json"; } 2>&1 )
  json=$(cat "$work/pack.json")
  read -r _ wall rss_kb <<<"$(grep '^TIME' <<<"$out")"
  /usr/bin/python3 - "$1" "$wall" "$rss_kb" "$json" "$2" <<'EOF'
import json, os, sys
label, wall, rss_kb, text, db = sys.argv[1:6]
j = json.loads(text)
largest = max((g["frames"] for g in j["groups"]), default=0)
print(f"| {label} | {j['clips']} | {j['frames']} | {os.path.getsize(db) / 1e6:.0f} MB | {len(j['groups'])} | "
      f"{largest} | {j['bytes']} | {j['max_cm']:.5f} | {float(wall):.1f} | {int(rss_kb) / 1024:.0f} MB |")
EOF
}

for k in $(seq "$copies"); do make_copy "$k"; done
import "$work/one.h5" "$work/copies/1/amc" "$work/copies/1/bvh"
folders=()
for k in $(seq "$copies"); do folders+=("$work/copies/$k/amc" "$work/copies/$k/bvh"); done
import "$work/many.h5" "${folders[@]}"

echo "| collection | clips | frames | file before pack | groups | largest group (frames) | packed bytes | max cm | pack wall s | peak RSS |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
measure "shared folders (1x)" "$work/one.h5"
measure "${copies}x" "$work/many.h5"
