#!/usr/bin/env bash
# Refreshes tests/costs/<kind>.txt (the test costs a fresh build starts ctest with; see
# tests/CMakeLists.txt) from a build folder's last full ctest run on CI's 2-core machine.
#   tools/test_costs.sh build release      tools/test_costs.sh build-asan sanitize
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?build folder}
kind=${2:?release or sanitize}
case "$kind" in release|sanitize) ;; *) echo "kind: release or sanitize" >&2; exit 2 ;; esac
data="$build/Testing/Temporary/CTestCostData.txt"
[ -f "$data" ] || { echo "$data: no ctest run recorded there" >&2; exit 2; }
# "name runs cost" up to the "---" that starts the failed list; one run each, longest first.
# Only the tests the build defines now (the data keeps the names of tests since removed or renamed).
current=$(mktemp)
trap 'rm -f "$current"' EXIT
(cd "$build" && ctest -N) | sed -n 's/^ *Test *#[0-9]*: \([^ ]*\).*/\1/p' > "$current"
# A name may appear more than once there: the largest cost counts.
awk 'NR == FNR { keep[$1] = 1; next } /^---/{exit} NF==3 && ($1 in keep) && $3 > cost[$1] { cost[$1] = $3 }
     END { for (name in cost) print name" 1 "cost[name] }' "$current" "$data" |
  sort -k3 -g -r > "tests/costs/$kind.txt"
echo "tests/costs/$kind.txt: $(wc -l < "tests/costs/$kind.txt") tests"
