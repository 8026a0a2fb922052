#!/usr/bin/env bash
# The main job, end to end. For now (until synthesis lands): describe a CMU clip, convert it from
# ASF/AMC to BVH and read the BVH back; then store subject 16's walks in a motion database, build a
# motion set with measured turn and speed, and time-align it into a pose tensor.
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
echo "== mocapdb import (subject 16's walks) -> $out/walks.h5"
walks=()
for t in 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30 31 32 33 34 47; do walks+=("$data/16_$t.amc"); done
"$mocapdb" import "${walks[@]}" -o "$out/walks.h5" --force
echo
echo "== mocapdb set create / align"
"$mocapdb" set create "$out/walks.h5" --name walks --clips '16_*' --extract turn speed displacement
"$mocapdb" align "$out/walks.h5" --set walks --frames 100 --method dtw
"$mocapdb" set show "$out/walks.h5" walks
echo
"$mocapdb" info "$out/walks.h5"
echo
echo "demo: outputs are in $out/ (16_15.bvh opens in Blender: File > Import > Motion Capture (.bvh);"
echo "      walks.h5 holds the clips, the set and its tensor: see README.md for reading it with h5py)"
