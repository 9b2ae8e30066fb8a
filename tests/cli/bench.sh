#!/usr/bin/env bash
# The benchmark script (bench/run_bench.sh) on the top-level examples, one run each: a row for every
# example with an expected volume (brep_box_hole included, from the STEP file bench_inputs writes),
# each ok and within its spec's _rel_tol (1e-6 when absent, as tests/bridge_cases.cpp checks the
# examples). Times are printed, never checked here.
# shellcheck source=tests/cli/lib.sh
. "$(dirname "$0")/lib.sh" "$@"

out="$TMP/bench.md"
RC=0
bash "$SRC/bench/run_bench.sh" "$SWEEPVOL" 1 >"$out" 2>"$TMP/last.err" || RC=$?
if [ "$RC" = 0 ]; then pass "run_bench.sh: exit 0"; else fail "run_bench.sh" "exit $RC"; fi

"$PYTHON" - "$out" "$SRC/examples" >"$TMP/rows.txt" <<'PY'
import glob, json, os, sys
rows = {}
for line in open(sys.argv[1]):
    cells = [c.strip() for c in line.strip().strip("|").split("|")]
    if len(cells) == 6 and cells[0] not in ("case", "---"):
        rows[cells[0]] = cells
for path in sorted(glob.glob(os.path.join(sys.argv[2], "*.json"))):
    spec = json.load(open(path))
    if "_expected_volume" not in spec:
        continue
    name = os.path.basename(path)[:-5]
    tol = float(spec.get("_rel_tol", 1e-6))
    r = rows.get(name)
    if r is None:
        print(f"FAIL {name}: no row")
    elif r[4] != "ok" or not float(r[3]) <= tol:
        print(f"FAIL {name}: status {r[4]}, relative error {r[3]} (allowed {tol:g})")
    else:
        print(f"ok {name}: relative error {r[3]}, {r[1]} s")
PY
while read -r verdict rest; do
  if [ "$verdict" = ok ]; then pass "$rest"; else fail "${rest%%:*}" "${rest#*: }"; fi
done <"$TMP/rows.txt"
grep -q '^ok brep_box_hole' "$TMP/rows.txt" && pass "brep_box_hole timed from bench_inputs' STEP file" ||
  fail "brep_box_hole" "no ok row"
finish
