#!/bin/bash
# The Python of the figures, the studies and the report machinery: pyflakes-clean, and imports in
# one direction — plots/ imports no study and no report machinery, reports/core/ imports no study,
# and nothing reaches a module through sys.path or importlib (each runs with `python3 -m` from the
# repository root).
set -euo pipefail
cd "$(dirname "$0")/../.."
status=0
trees=(plots reports experiments tests/reports tests/python python/dabench examples scripts)
if ! pyflakes3 "${trees[@]}"; then
  echo "python_lint: pyflakes3 found the problems above" >&2
  status=1
fi
forbidden() {  # forbidden PATTERN WHY FOLDER...
  local pattern=$1 why=$2
  shift 2
  if grep -rnE --include='*.py' "$pattern" "$@"; then
    echo "python_lint: $why" >&2
    status=1
  fi
}
forbidden '^\s*(from|import)\s+(reports|experiments)\b' "plots/ imports a study or the report machinery (figures are functions of data)" plots
forbidden '^\s*(from|import)\s+experiments\b' "reports/core/ imports a study" reports/core
forbidden 'sys\.path\.(insert|append)|importlib' "a module found through sys.path or importlib" plots reports experiments tests/reports
exit $status
