#!/usr/bin/env bash
# Fails when any tracked C++ file differs from what .clang-format asks for.
set -euo pipefail
cd "$(dirname "$0")/.."
files=$(git ls-files '*.h' '*.hpp' '*.cpp' '*.cc')
[[ -z $files ]] && exit 0
# shellcheck disable=SC2086
if ! clang-format --dry-run --Werror $files; then
  echo "clang-format: run scripts/format.sh" >&2
  exit 1
fi
echo "clang-format: ok"
