#!/usr/bin/env bash
# Builds the examples' database from the shared CMU walks of subject 16 with the mocapdb CLI: import,
# a motion set of gait cycles by turn and speed, alignment, the Tucker model and the packed tier.
# Usage: make_example_db.sh MOCAPDB_CLI SHARED_DIR OUT.h5   (exit 77: the shared data is missing)
set -euo pipefail
cli=$1 shared=$2 out=$3
amc="$shared/datasets/cmu-asfamc"
if [ ! -f "$amc/16_11.amc" ]; then
  echo "skipped: shared data not found at $amc"
  exit 77
fi
rm -f "$out"
files=()
for t in 11 12 13 14 15 16 17 18 19 20 21 22 23 24; do files+=("$amc/16_$t.amc"); done
"$cli" import "${files[@]}" -o "$out"
"$cli" set create "$out" --name walks --clips '16_*' --extract turn speed
"$cli" align "$out" --set walks --frames 40
"$cli" compress "$out" --set walks --max-error-cm 1
"$cli" pack "$out" --max-error-cm 1
