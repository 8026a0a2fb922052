#!/usr/bin/env bash
# The main job, end to end: install what is missing, build the command-line tool (Release),
# and run `mocapdb demo`: a procedural parametric motion set of the built-in humanoid (or, with
# --data DIR, the clips of a folder) imported into OUT/demo.h5, made a motion set, time-aligned,
# compressed, reported (rate-distortion table), and synthesized at new parameters; BVH files, SVG
# plots, report.json and README.txt are written to OUT.
# Usage: scripts/demo.sh [OUT] [mocapdb demo options, e.g. --motion walk, --data DIR, --quick]
#        (OUT defaults to demo-out, relative to the current folder; outputs of an earlier demo there are
#        replaced). MOCAPDB_BUILD_DIR chooses the build folder (default build/release).
set -euo pipefail
out="${1:-demo-out}"
[ $# -gt 0 ] && shift
out="$(realpath -m -- "$out")"
cd "$(dirname "$0")/.."

scripts/setup.sh
build="${MOCAPDB_BUILD_DIR:-build/release}"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc)" --target mocapdb_cli

"$build/tools/mocapdb" demo --out "$out" --force "$@"

echo
echo "demo: outputs are in $out/ (README.txt there says what each file is):"
ls -l "$out"
echo "demo: open the synth_*.bvh files in Blender (File > Import > Motion Capture (.bvh)) and the .svg files in a browser"
