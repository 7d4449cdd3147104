#!/usr/bin/env bash
# Fails, listing the files, if any C++ or OpenCL source under src/, kernels/,
# tests/ or fuzz/ differs from what clang-format 14 makes of it (.clang-format at
# the top). The version is pinned: other versions format some constructs
# differently. Fix with: clang-format-14 -i FILE...
set -euo pipefail
cd "$(dirname "$0")/.."
format=clang-format-14
if ! command -v "$format" >/dev/null; then
  format=clang-format
  if ! "$format" --version 2>/dev/null | grep -q "version 14\."; then
    echo "check-format: clang-format 14 is needed (Debian package clang-format-14)" >&2
    exit 2
  fi
fi
mapfile -t files < <(find src kernels tests fuzz -type f \
  \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.cl' \) | sort)
unformatted=()
for f in "${files[@]}"; do
  "$format" --dry-run --Werror "$f" >/dev/null 2>&1 || unformatted+=("$f")
done
if ((${#unformatted[@]})); then
  echo "check-format: not clang-format clean (${#unformatted[@]} of ${#files[@]} files):" >&2
  printf '  %s\n' "${unformatted[@]}" >&2
  exit 1
fi
echo "check-format: ${#files[@]} files clean"
