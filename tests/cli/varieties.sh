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

sv varieties "$SRC/examples/box_revolve_90.json" --faces "$TMP/v.xyz"
if [ "$RC" = 2 ] && stderr_has "--faces"; then pass "bad --faces extension: exit 2"; else fail "bad --faces" "exit $RC"; fi

finish
