#!/usr/bin/env bash
# The C++ style check: every tracked C++ file of lib/, json/, serve/, tools/ and python/ as .clang-format says.
# Usage: scripts/check_format.sh [--fix]   (--fix rewrites the files in place instead of failing)
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files 'lib/*.cpp' 'lib/*.hpp' 'lib/*.h' 'json/*.cpp' 'json/*.hpp' 'serve/*.cpp' \
  'serve/*.hpp' 'tools/*.cpp' 'tools/*.hpp' 'python/*.cpp' 'python/*.hpp')
if [ ${#files[@]} -eq 0 ]; then
  echo "check_format: no C++ files found (not a git checkout?)" >&2
  exit 1
fi
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
else
  clang-format --dry-run -Werror "${files[@]}"
  echo "check_format: ${#files[@]} files follow .clang-format"
fi
