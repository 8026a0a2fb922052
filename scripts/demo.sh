#!/usr/bin/env bash
# The main job, end to end. For now (until synthesis lands): describe a CMU clip, convert it from
# ASF/AMC to BVH, and read the BVH back.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/release -j "$(nproc)" --target mocapdb_cli

data=../shared/datasets/cmu-asfamc
out=out/demo
if [ ! -d "$data" ]; then
  echo "demo: the shared CMU data is not at $data (expected beside this repository)" >&2
  exit 1
fi
mkdir -p "$out"
mocapdb=build/release/tools/mocapdb

echo "== mocapdb info $data/16_15.amc"
"$mocapdb" info "$data/16_15.amc" --asf "$data/16.asf"
echo
echo "== mocapdb convert (ASF/AMC -> BVH)"
"$mocapdb" convert "$data/16_15.amc" --asf "$data/16.asf" -o "$out/16_15.bvh" --force
echo
echo "== mocapdb info $out/16_15.bvh"
"$mocapdb" info "$out/16_15.bvh"
echo
echo "demo: outputs are in $out/ (16_15.bvh opens in Blender: File > Import > Motion Capture (.bvh))"
