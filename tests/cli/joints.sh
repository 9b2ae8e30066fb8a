#!/usr/bin/env bash
# `sweepvol joints`: the SPEC.md JSON shape, the DOT graph, and a motion that `sweepvol run` sweeps.
# shellcheck source=tests/cli/lib.sh
. "$(dirname "$0")/lib.sh" "$@"
J=$SRC/examples/joints

sv joints "$J/revolute.json" --json
cp "$TMP/last.out" "$TMP/rev.json"
if [ "$RC" = 0 ] && [ "$(json_get "$TMP/rev.json" 'r["joints"][0]["type"]')" = revolute ] &&
   [ "$(json_get "$TMP/rev.json" 'r["joints"][0]["dof"]')" = 1 ] &&
   [ "$(json_get "$TMP/rev.json" '[p["dof"] for p in r["parts"] if p["name"] == "crank"][0]')" = 1 ]; then
  pass "revolute: type, dof and part mobility"
else
  fail "revolute" "exit $RC, $(head -c 300 "$TMP/rev.json")"
fi

sv joints "$J/grab.json" --json --dot "$TMP/grab.dot"
if [ "$RC" = 0 ] && grep -q -- "--" "$TMP/grab.dot" && [ "$(grep -c -- '--' "$TMP/grab.dot")" -ge 15 ]; then
  pass "grab: DOT graph with 15 joints"
else
  fail "grab dot" "exit $RC"
fi

# the motion of the crank, put into a spec and swept: a box [1,2]x[0,1]x[0,1] turned 90 degrees
sv joints "$J/revolute.json" --motion-for crank --range ground-crank=0,90
cp "$TMP/last.out" "$TMP/motion.json"
"$PYTHON" - "$TMP/motion.json" "$TMP/spec.json" <<'PY'
import json, sys
motion = json.load(open(sys.argv[1]))
spec = {"sweep": 1, "angles": "deg", "entity": {"kind": "box", "min": [1, 0, 0], "max": [2, 1, 1]}, "motion": motion}
json.dump(spec, open(sys.argv[2], "w"))
PY
sv run "$TMP/spec.json" --report "$TMP/r.json"
if [ "$RC" = 0 ] && rel_close "$(json_get "$TMP/r.json" 'r["volume"]["brep"]')" 4.141592653589793 1e-9; then
  pass "motion-for: the crank's motion sweeps the box to 1 + pi"
else
  fail "motion-for" "exit $RC"
fi

# bad input: unknown part in a constraint
"$PYTHON" - "$TMP/bad.json" <<'PY'
import json, sys
a = {"assembly": 1, "parts": ["ground", "crank"], "ground": "ground",
     "constraints": [{"type": "coplanar", "parts": ["ground", "crankk"],
                      "plane1": {"point": [0, 0, 0], "normal": [0, 0, 1]},
                      "plane2": {"point": [0, 0, 0], "normal": [0, 0, -1]}}]}
json.dump(a, open(sys.argv[1], "w"))
PY
sv joints "$TMP/bad.json"
if [ "$RC" = 2 ] && stderr_has "/constraints/0/parts"; then
  pass "unknown part: exit 2 naming the pointer"
else
  fail "unknown part" "exit $RC"
fi

finish
