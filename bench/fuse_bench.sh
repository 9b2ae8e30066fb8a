#!/usr/bin/env bash
# Side by side: sweepvol against the fuse of N+1 placed copies (what a FreeCAD user does today),
# on one-joint examples. Prints a markdown table: case, method, seconds, volume error.
# Usage: bench/fuse_bench.sh [build dir] [N...]   (default build/, N = 8 16 32)
# Environment: FUSE_CASES (spec files, default four examples), FUSE_TIMEOUT (seconds per fuse).
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$ROOT/build}
shift || true
NS=${*:-8 16 32}
FUSE_TIMEOUT=${FUSE_TIMEOUT:-1800}
CASES=${FUSE_CASES:-"$ROOT/examples/cylinder_flip.json $ROOT/examples/box_revolve_90.json $ROOT/examples/cylinder_parallel_revolve.json $ROOT/examples/sphere_spring.json"}

for tool in "$BUILD/bin/sweepvol" "$BUILD/bin/fuse_copies"; do
  [ -x "$tool" ] || { echo "fuse_bench.sh: not built: $tool" >&2; exit 2; }
done
TMP=$(mktemp -d "${TMPDIR:-/tmp}/sweep-fuse.XXXXXX")
trap 'rm -rf "$TMP"' EXIT

echo "| case | method | seconds | rel. volume error |"
echo "|---|---|---|---|"
for spec in $CASES; do
  name=$(basename "$spec" .json)
  t0=$(date +%s.%N)
  status=0
  "$BUILD/bin/sweepvol" run "$spec" --report "$TMP/r.json" >/dev/null 2>&1 || status=$?
  t1=$(date +%s.%N)
  python3 - "$spec" "$TMP/r.json" "$status" "$(echo "$t1 - $t0" | bc)" <<'PY'
import json, sys
spec, report, status, secs = sys.argv[1:5]
ref = json.load(open(spec))["_expected_volume"]
name = spec.rsplit("/", 1)[-1][:-5]
try:
    r = json.load(open(report))
    err = "%+.1e (%s)" % ((r["volume"]["brep"] - ref) / abs(ref), r["status"])
except Exception:
    err = "exit %s" % status
print("| %s | sweepvol | %.2f | %s |" % (name, float(secs), err))
PY
  for n in $NS; do
    row=$(timeout "$FUSE_TIMEOUT" "$BUILD/bin/fuse_copies" "$spec" "$n" 2>/dev/null) || row=""
    if [ -z "$row" ]; then
      echo "| $name | fuse of $((n + 1)) copies | > $FUSE_TIMEOUT | (no result) |"
    else
      echo "$row" | awk -F'|' -v c=$((n + 1)) '{for (i = 2; i <= 6; i++) gsub(/^ +| +$/, "", $i); printf "| %s | fuse of %d copies | %s | %s |\n", $2, c, $4, $6}'
    fi
  done
done
