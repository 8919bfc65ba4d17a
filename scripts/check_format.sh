#!/usr/bin/env bash
# Every C++ source the project tracks is clang-formatted (.clang-format at the root); lists the
# files that are not and exits 1. Fix with: git ls-files '*.h' '*.cpp' | xargs clang-format -i
set -euo pipefail
root="${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}"
cd "$root"
fmt="$(command -v clang-format || command -v clang-format-14 || true)"
[ -n "$fmt" ] || { echo "check_format: clang-format not found (Debian package clang-format)" >&2; exit 1; }
mapfile -t files < <(git ls-files '*.h' '*.cpp' 2>/dev/null || find sim policies viz apps bench tests \( -name '*.h' -o -name '*.cpp' \))
bad=()
for f in "${files[@]}"; do
  "$fmt" --dry-run -Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done
if [ ${#bad[@]} -gt 0 ]; then
  printf 'not clang-formatted: %s\n' "${bad[@]}"
  exit 1
fi
echo "check_format: ${#files[@]} files clang-formatted"
