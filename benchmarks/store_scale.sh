#!/usr/bin/env bash
# Store operations on a database of thousands of clips (issue 16, acceptance 3): append one clip,
# `info`, a 100-sample set, `validate`. Targets: append <= 2 s, set <= 5 s, info <= 2 s.
#
# Generates GRID_TURN x 60 procedural walks (`mocapdb generate walk`, 52 turns -> 3 120 clips: 3 119
# in the base database, the last one appended), imports them once, then times each operation on a
# fresh copy of that database's index (wall and user CPU seconds from /usr/bin/time, the whole
# process). Format 4: the copy's links lead to base.h5.d's segments, which no operation here changes
# (what a write adds goes to copy.h5.d).
# The set takes the clips 'walk_s1[0-1]*' (speeds 1.00-1.19: about 470 samples, more than the 100
# of the target) and extracts speed and turn.
#
# Usage: benchmarks/store_scale.sh [BUILD_DIR=build/release] [WORK_DIR=/tmp/mocapdb-store-scale] [GRID_TURN=52]
# Needs /usr/bin/time (Debian package time); about 250 MB of disk in WORK_DIR.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
work=${2:-/tmp/mocapdb-store-scale}
turns=${3:-52}
cli="$build/tools/mocapdb"
[ -x "$cli" ] || { echo "store_scale.sh: no $cli (build first)" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "store_scale.sh: /usr/bin/time not found (apt-get install time)" >&2; exit 2; }

if [ ! -f "$work/base.h5" ]; then
  rm -rf "$work"
  mkdir -p "$work"
  "$cli" generate walk --out "$work/gen" --grid speed=0.5:1.9:60 "turn=-150:150:$turns" --cycles 1 --precision 6 >/dev/null
  mkdir -p "$work/one"
  last=$(ls "$work/gen" | grep '\.bvh$' | sort | tail -1)
  mv "$work/gen/$last" "$work/one/"
  "$cli" import "$work/gen" -o "$work/base.h5" >/dev/null
fi
clips=$("$cli" info "$work/base.h5" --json | /usr/bin/python3 -c 'import json,sys; print(len(json.load(sys.stdin)["clips"]))' 2>/dev/null || echo "?")

timed() {  # $1 = label, then the command
  local label=$1; shift
  /usr/bin/time -o "$work/time.txt" -f "%e %U %S %M" "$@" >/dev/null 2>"$work/stderr.txt" ||
    { echo "store_scale.sh: $label failed:" >&2; cat "$work/stderr.txt" >&2; exit 1; }
  read -r wall user sys rss <"$work/time.txt"
  printf "| %s | %s | %s | %s | %s |\n" "$label" "$wall" "$user" "$sys" "$((rss / 1024))"
}

echo "database: $work/base.h5 ($clips clips, $(du -cm "$work/base.h5" "$work/base.h5.d" | tail -1 | cut -f1) MB with its segments, index $(du -k "$work/base.h5" | cut -f1) kB); $(date -u '+%F %H:%M UTC'); load $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| operation | wall s | user s | sys s | peak RSS MB |"
echo "|---|---:|---:|---:|---:|"
db="$work/copy.h5"
rm -rf "$db.d"
cp "$work/base.h5" "$db"
timed "append one clip (import)" "$cli" import "$work/one" -o "$db"
timed "info" "$cli" info "$db"
timed "set create (--clips 'walk_s1[0-1]*', speed turn)" "$cli" set create "$db" --name s100 --clips 'walk_s1[0-1]*' --segment none --extract speed turn
timed "validate" "$cli" validate "$db"
rm -rf "$db.d"
cp "$work/base.h5" "$db"
timed "re-import the whole folder (all duplicates)" "$cli" import "$work/gen" -o "$db"
rm -rf "$db" "$db.lock" "$db.d"
