#!/usr/bin/env bash
# Times `sweepvol run` on every examples/*.json that has an `_expected_volume` and prints a
# markdown table (see bench/README.md).
# Usage: bench/run_bench.sh [build/bin/sweepvol] [runs]
# Environment: BENCH_EXAMPLES (folder of specs, default examples/), BENCH_TIMEOUT (seconds per run).
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
SWEEPVOL=${1:-$ROOT/build/bin/sweepvol}
RUNS=${2:-5}
PYTHON=${PYTHON:-python3}
BENCH_TIMEOUT=${BENCH_TIMEOUT:-1800}        # seconds allowed for one run
EXAMPLES=${BENCH_EXAMPLES:-$ROOT/examples}  # folder of specs

if [ ! -x "$SWEEPVOL" ]; then
  echo "run_bench.sh: not an executable: $SWEEPVOL" >&2
  exit 2
fi
if ! [[ "$RUNS" =~ ^[1-9][0-9]*$ ]]; then
  echo "run_bench.sh: runs must be a positive integer (got '$RUNS')" >&2
  exit 2
fi

TMP=$(mktemp -d "${TMPDIR:-/tmp}/sweep-bench.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
# The files some examples refer to and the repository does not hold (box_hole.step), written by
# bench_inputs from the same build; such a spec is timed from a copy beside them.
INPUTS="$TMP/inputs"
mkdir -p "$INPUTS"
BENCH_INPUTS="$(dirname "$SWEEPVOL")/bench_inputs"
if [ -x "$BENCH_INPUTS" ]; then
  "$BENCH_INPUTS" "$INPUTS" >/dev/null || echo "run_bench.sh: $BENCH_INPUTS failed" >&2
fi

# spec_info SPEC: prints the expected volume, or nothing when the spec has none; exits 3 when a
# file the spec refers to (entity, spine or motion "file") does not exist.
spec_info() {
  "$PYTHON" - "$1" <<'EOF'
import json, os, sys
path = sys.argv[1]
spec = json.load(open(path))
if "_expected_volume" not in spec:
    sys.exit(0)
def files(node):
    if isinstance(node, dict):
        for k, v in node.items():
            if k == "file" and isinstance(v, str):
                yield v
            else:
                yield from files(v)
    elif isinstance(node, list):
        for v in node:
            yield from files(v)
base = os.path.dirname(os.path.abspath(path))
for f in files({"entity": spec.get("entity"), "motion": spec.get("motion")}):
    if not os.path.exists(os.path.join(base, f)):
        print(f, file=sys.stderr)
        sys.exit(3)
print(repr(float(spec["_expected_volume"])))
EOF
}

# row NAME EXPECTED REPORT_OR_EMPTY EXIT_CODE SECONDS...: prints one table row.
row() {
  "$PYTHON" - "$@" <<'EOF'
import json, statistics, sys
name, expected, report, code = sys.argv[1:5]
secs = [float(s) for s in sys.argv[5:]]
expected = float(expected)
median = f"{statistics.median(secs):.3f}" if secs else "-"
vol = err = faces = "-"
status = f"exit {code}"
try:
    r = json.load(open(report))
    status = r.get("status", status) if code in ("0", "3") else status
    v = r.get("volume", {}).get("brep")
    if v is not None:
        vol = f"{v:.12g}"
        err = f"{abs(v - expected) / abs(expected):.2e}"
    faces = str(r.get("faces", "-"))
except (OSError, ValueError):
    pass
print(f"| {name} | {median} | {vol} | {err} | {status} | {faces} |")
EOF
}

echo "sweepvol: $SWEEPVOL ($("$SWEEPVOL" --version 2>/dev/null || echo "version unknown")), $RUNS runs per case, $(nproc) cores"
echo
echo "| case | median s | volume.brep | rel. error | status | faces |"
echo "|---|---:|---:|---:|---|---:|"
for spec in "$EXAMPLES"/*.json; do
  name=$(basename "$spec" .json)
  rc=0
  expected=$(spec_info "$spec" 2>"$TMP/missing") || rc=$?
  if [ "$rc" -eq 3 ] && [ -e "$INPUTS/$(cat "$TMP/missing")" ]; then
    cp "$spec" "$INPUTS/"
    spec="$INPUTS/$(basename "$spec")"
    rc=0
    expected=$(spec_info "$spec" 2>"$TMP/missing") || rc=$?
  fi
  if [ "$rc" -eq 3 ]; then
    echo "skipping $name: missing $(cat "$TMP/missing")" >&2
    continue
  elif [ "$rc" -ne 0 ]; then
    echo "skipping $name: unreadable spec" >&2
    continue
  fi
  [ -n "$expected" ] || continue
  secs=()
  code=0
  report="$TMP/$name.json"
  for ((i = 0; i < RUNS; ++i)); do
    rm -f "$report"
    t0=$(date +%s.%N)
    code=0
    timeout "$BENCH_TIMEOUT" "$SWEEPVOL" run "$spec" --report "$report" >/dev/null 2>"$TMP/stderr" || code=$?
    t1=$(date +%s.%N)
    secs+=("$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.6f", b - a }')")
    # A run that does not finish normally is not repeated.
    if [ "$code" -ne 0 ] && [ "$code" -ne 3 ]; then break; fi
  done
  row "$name" "$expected" "$report" "$code" "${secs[@]}"
done
