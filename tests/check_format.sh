#!/usr/bin/env bash
# Every tracked C/CUDA source is formatted as .clang-format says (clang-format --dry-run --Werror).
set -u
cd "$(dirname "$0")/.." || exit 1
command -v clang-format >/dev/null || { echo "skipped: clang-format not found"; exit 77; }
git rev-parse --git-dir >/dev/null 2>&1 || { echo "skipped: not a git checkout"; exit 77; }
files=$(git ls-files '*.c' '*.h' '*.cu' '*.cuh')
bad=$(clang-format --dry-run --Werror $files 2>&1 | grep -o '^[^:]*:[0-9]*:[0-9]*: error' | cut -d: -f1 | sort -u)
if [ -n "$bad" ]; then
  echo "not clang-formatted (run clang-format -i on them):"
  echo "$bad"
  exit 1
fi
echo "$(echo "$files" | wc -w) files clang-formatted"
