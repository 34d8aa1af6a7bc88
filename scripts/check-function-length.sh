#!/usr/bin/env bash
# Fails when a function in engine/, baker/ or bench/ is longer than 120 lines, by universal-ctags' line and end
# fields (the rule in docs/development.md: split by meaning, small functions with one job). Usage:
#   scripts/check-function-length.sh [max_lines]
set -euo pipefail
cd "$(dirname "$0")/.."
max_lines="${1:-120}"
if ! command -v ctags >/dev/null || ! ctags --version 2>/dev/null | grep -q "Universal Ctags"; then
  echo "check-function-length: universal-ctags is needed (apt-get install universal-ctags)" >&2
  exit 1
fi
too_long=$(git ls-files 'engine/*.cpp' 'engine/*.h' 'baker/*.cpp' 'baker/*.h' 'bench/*.cpp' 'bench/*.h' |
  ctags -L - -x --_xformat='%F %n %{end} %N' --kinds-C++=f --fields=+ne -o - |
  awk -v max="$max_lines" '$3 != "" && $3 - $2 + 1 > max { printf "%s:%s %s: %d lines\n", $1, $2, $4, $3 - $2 + 1 }')
if [ -n "$too_long" ]; then
  echo "check-function-length: functions over $max_lines lines:" >&2
  echo "$too_long" >&2
  exit 1
fi
echo "check-function-length: no function in engine/, baker/ or bench/ is over $max_lines lines"
