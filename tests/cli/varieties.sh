#!/usr/bin/env bash
# `sweepvol varieties`: the JSON listing and the candidate faces written for display.
# shellcheck source=tests/cli/lib.sh
. "$(dirname "$0")/lib.sh" "$@"

sv varieties "$SRC/examples/sphere_extrude.json" -o "$TMP/v.json" --faces "$TMP/v.brep"
if [ "$RC" = 0 ] && [ -s "$TMP/v.brep" ] &&
   [ "$(json_get "$TMP/v.json" 'sorted({v["type"] for v in r["varieties"]})')" = "['interior', 'limit']" ] &&
   rel_close "$(json_get "$TMP/v.json" 'r["volume_from_varieties"]')" "$(json_get "$TMP/v.json" 'r["volume"]["divergence"]')" 1e-9; then
  pass "capsule: limit and interior varieties, contributions add up to the volume"
else
  fail "capsule varieties" "exit $RC"
fi

# a solid under a path that is no screw: no solid yet, but its candidate patches are listed
cat > "$TMP/roll.json" <<'JSON'
{"sweep": 1, "entity": {"kind": "cylinder", "base": [0, 0, -1], "axis": [0, 0, 1], "radius": 0.5, "height": 2},
 "motion": {"kind": "path", "t": [0, 1], "translate": ["0", "4*t", "0"], "rotate": [{"axis": [1, 0, 0], "angle": "pi*t"}]}}
JSON
sv varieties "$TMP/roll.json" -o "$TMP/roll_v.json" --faces "$TMP/roll_v.brep"
if [ "$RC" = 3 ] && [ ! -e "$TMP/roll_v.brep" ] && stderr_has "candidate varieties are listed" &&
   [ "$(json_get "$TMP/roll_v.json" 'sorted({v["type"] for v in r["varieties"]})')" = "['boundary', 'interior', 'limit']" ] &&
   rel_close "$(json_get "$TMP/roll_v.json" 'sum(v["area"] for v in r["varieties"] if v["type"] == "limit")')" \
     "$(python3 -c 'import math; print(2 * (2 * math.pi * 0.5 * 2 + 2 * math.pi * 0.25))')" 1e-9; then
  pass "rolling cylinder: candidate patches listed (limit, boundary, interior), no solid, no faces file"
else
  fail "rolling cylinder varieties" "exit $RC"
fi

sv varieties "$SRC/examples/box_revolve_90.json" --faces "$TMP/v.xyz"
if [ "$RC" = 2 ] && stderr_has "--faces"; then pass "bad --faces extension: exit 2"; else fail "bad --faces" "exit $RC"; fi

finish
