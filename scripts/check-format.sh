#!/usr/bin/env bash
# Every C++ source of the project (app, bench, core, tests) as the one .clang-format wants it.
# Prints each file that is not, with the command that fixes it, and exits 1; ctest runs it
# (SourceFormat), so drift fails the suite instead of piling up (eight files had drifted when
# this check was added).
set -euo pipefail
cd "$(dirname "$0")/.."
format=${CLANG_FORMAT:-clang-format}
if ! command -v "$format" >/dev/null; then
  echo "$format not found: ./dev test installs it (Debian package clang-format)" >&2
  exit 1
fi
status=0
while IFS= read -r -d '' file; do
  if ! "$format" --dry-run -Werror "$file" >/dev/null 2>&1; then
    echo "not formatted: $file (fix: $format -i $file)" >&2
    status=1
  fi
done < <(find app bench core tests -type f \( -name '*.cpp' -o -name '*.h' \) -print0 | sort -z)
exit $status
