#!/usr/bin/env bash
# The whole test suite: install what is missing, then
#   0. the style check (.clang-format);
#   1. Release build (gcc, warnings as errors) and every CTest test;
#   2. the same suite under AddressSanitizer + UndefinedBehaviorSanitizer (clang), plus bounded
#      libFuzzer runs of the file parsers on their seed corpora.
# Usage: scripts/test.sh [--fast]   (--fast skips the sanitizer pass)
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh

jobs=$(nproc)
fast=0
[ "${1:-}" = "--fast" ] && fast=1

echo "== style (clang-format --dry-run -Werror on the C++ of lib/, json/, serve/, tools/, python/)"
scripts/check_format.sh

echo "== release build (warnings are errors)"
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DMOCAPDB_WERROR=ON >/dev/null
cmake --build build/release -j "$jobs"
echo "== release tests"
ctest --test-dir build/release --output-on-failure -j "$jobs"

if [ "$fast" = 1 ]; then
  exit 0
fi

echo "== sanitizer build (clang, ASan + UBSan, libFuzzer targets)"
# Line tables only: the sanitizers' reports name file and line; full debug info would add a third to the
# compile time (benchmarks/RESULTS.md, "Build and CI time").
CC=clang CXX=clang++ cmake -S . -B build/sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
  -DMOCAPDB_SANITIZE=ON -DMOCAPDB_FUZZ=ON -DMOCAPDB_WERROR=ON -DMOCAPDB_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build/sanitize -j "$jobs"
echo "== sanitizer tests and bounded fuzz runs"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build/sanitize --output-on-failure -j "$jobs"
