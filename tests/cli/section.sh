#!/usr/bin/env bash
# `sweepvol section` (areas of cross-sections against closed forms, the SVG drawing, bad input) and
# `sweepvol varieties --svg`.
PYTHON=${PYTHON:-/usr/bin/python3}
# shellcheck source=tests/cli/lib.sh
. "$(dirname "$0")/lib.sh" "$@"

# svg_check FILE EXPR: EXPR (Python, `d` = the parsed document) is true for the well-formed SVG FILE.
svg_check() {
  "$PYTHON" -c 'import sys, xml.dom.minidom
d = xml.dom.minidom.parse(sys.argv[1])
sys.exit(0 if eval(sys.argv[2]) else 1)' "$1" "$2"
}
PANELS='[g for g in d.getElementsByTagName("g") if g.getAttribute("class") == "panel"]'

# Box [1,2]x[0,1]x[0,1] revolved 90 degrees about z: for 0 < z < 1 the section is the unit square
# swept a quarter turn in its plane, area 1 + (pi/2)/2 (rmax^2 - rmin^2) = 1 + pi (every circle
# about z meets the square in one arc), one loop, box [-1, 0] x [2, sqrt 5].
sv section "$SRC/examples/box_revolve_90.json" --z 0.25,0.75,1.5 --svg "$TMP/box.svg" -o "$TMP/box.json"
if [ "$RC" = 0 ] && cmp -s "$TMP/last.out" "$TMP/box.json"; then pass "box: exit 0, JSON printed and written"; else fail "box section" "exit $RC"; fi
ok=1
for k in 0 1; do
  rel_close "$(json_get "$TMP/box.json" "r['sections'][$k]['area']")" "$("$PYTHON" -c 'import math; print(1 + math.pi)')" 1e-6 || ok=0
  [ "$(json_get "$TMP/box.json" "r['sections'][$k]['loops']")" = 1 ] || ok=0
done
json_get "$TMP/box.json" 'all(abs(a - b) < 1e-6 for a, b in zip(sum(r["sections"][0]["bbox"], []), [-1, 0, 2, 5 ** 0.5]))' | grep -q True || ok=0
[ "$(json_get "$TMP/box.json" 'r["sections"][2]["area"] == 0 and r["sections"][2]["loops"] == 0')" = True ] || ok=0
[ "$(json_get "$TMP/box.json" '[s["z"] for s in r["sections"]] == [0.25, 0.75, 1.5] and r["status"] == "ok" and r["sweep_section"] == 1')" = True ] || ok=0
rel_close "$(json_get "$TMP/box.json" 'r["volume"]["brep"]')" 4.141592653589793 1e-9 || ok=0
if [ "$ok" = 1 ]; then pass "box: area 1 + pi at z = 0.25 and 0.75, one loop, exact box; empty at z = 1.5"; else fail "box areas" "$(cat "$TMP/box.json")"; fi
if svg_check "$TMP/box.svg" "len($PANELS) == 3 and all('z = ' in p.toxml() and 'area = ' in p.toxml() for p in $PANELS)" &&
   svg_check "$TMP/box.svg" 'len([p for p in d.getElementsByTagName("path") if p.getAttribute("fill-rule") == "evenodd" and p.getAttribute("d").startswith("M")]) == 2'; then
  pass "box: well-formed SVG, three titled panels, two filled even-odd paths (the third is empty)"
else
  fail "box SVG" "$(head -c 300 "$TMP/box.svg")"
fi

# A unit sphere moved by three prismatic joints over [0,2]x[0,3]x[0,4] (the rounded box): inside
# the height of the box the section is the 2 x 3 rectangle dilated by 1, area 6 + 2 (2 + 3) + pi;
# at a height h = 0.5 above its top, dilated by rho = sqrt(1 - h^2): 6 + 10 rho + pi rho^2.
sv section "$SRC/examples/chains/sphere_three_prismatic.json" --z=2,4.5,-1.5 -o "$TMP/rb.json" --svg "$TMP/rb.svg"
ok=1
[ "$RC" = 0 ] || ok=0
rel_close "$(json_get "$TMP/rb.json" 'r["sections"][0]["area"]')" "$("$PYTHON" -c 'import math; print(16 + math.pi)')" 1e-6 || ok=0
rel_close "$(json_get "$TMP/rb.json" 'r["sections"][1]["area"]')" \
  "$("$PYTHON" -c 'import math; r = math.sqrt(0.75); print(6 + 10 * r + math.pi * r * r)')" 1e-6 || ok=0
[ "$(json_get "$TMP/rb.json" 'r["sections"][2]["area"] == 0 and r["sections"][2]["loops"] == 0')" = True ] || ok=0
json_get "$TMP/rb.json" 'all(abs(a - b) < 1e-6 for a, b in zip(sum(r["sections"][0]["bbox"], []), [-1, -1, 3, 4]))' | grep -q True || ok=0
if [ "$ok" = 1 ]; then pass "rounded box: areas 16 + pi and 6 + 10 rho + pi rho^2 to 1e-6, empty below"; else fail "rounded box areas" "exit $RC $(cat "$TMP/rb.json" 2>/dev/null)"; fi
if svg_check "$TMP/rb.svg" "len($PANELS) == 3"; then pass "rounded box: SVG with three panels"; else fail "rounded box SVG" "not three panels"; fi

# varieties --svg: a legend entry per variety of the JSON, and the faces drawn.
sv varieties "$SRC/examples/chains/box_revolve_extrude.json" -o "$TMP/v.json" --svg "$TMP/v.svg"
n=$(json_get "$TMP/v.json" 'len(r["varieties"])' 2>/dev/null || echo 0)
if [ "$RC" = 0 ] && [ "$n" -gt 0 ] &&
   svg_check "$TMP/v.svg" "sorted(g.getAttribute('id') for g in d.getElementsByTagName('g') if g.getAttribute('class') == 'legend-entry' and g.getAttribute('id') != 'legend-unknown') == sorted('legend-v%d' % i for i in range(1, $n + 1))" &&
   svg_check "$TMP/v.svg" 'len([g for g in d.getElementsByTagName("g") if g.getAttribute("class") == "face"]) > 0 and "viewed from" in d.toxml()' &&
   [ "$(stat -c %s "$TMP/v.svg")" -lt 4000000 ]; then
  pass "varieties --svg: well-formed, $n legend entries (one per variety), faces drawn, view stated, < 4 MB"
else
  fail "varieties --svg" "exit $RC, $n varieties"
fi

# Bad input: exit 2, the option named, no output left behind.
bad() {  # bad NAME OPTION ARGS...
  local name=$1 opt=$2
  shift 2
  rm -f "$TMP"/out.*
  sv "$@"
  if [ "$RC" = 2 ] && stderr_has "$opt" && [ -z "$(ls "$TMP"/out.* 2>/dev/null)" ]; then
    pass "$name: exit 2 naming $opt, nothing written"
  else
    fail "$name" "exit $RC, files: $(ls "$TMP"/out.* 2>/dev/null)"
  fi
}
BOX=$SRC/examples/box_revolve_90.json
bad "--z missing" --z section "$BOX" --svg "$TMP/out.svg" -o "$TMP/out.json"
bad "--z without value" --z section "$BOX" --svg "$TMP/out.svg" --z
bad "--z empty" --z section "$BOX" --z "" --svg "$TMP/out.svg" -o "$TMP/out.json"
bad "--z non-numeric" --z section "$BOX" --z 0.5,abc --svg "$TMP/out.svg" -o "$TMP/out.json"
bad "--z empty item" --z section "$BOX" --z 0.5,,1 --svg "$TMP/out.svg" -o "$TMP/out.json"
bad "--z NaN" --z section "$BOX" --z nan --svg "$TMP/out.svg" -o "$TMP/out.json"
bad "--z inf" --z section "$BOX" --z 0.5,-inf --svg "$TMP/out.svg" -o "$TMP/out.json"
bad "--z overflow" --z section "$BOX" --z 1e999 --svg "$TMP/out.svg" -o "$TMP/out.json"
bad "--svg not .svg" --svg section "$BOX" --z 0.5 --svg "$TMP/out.png" -o "$TMP/out.json"
bad "--svg without name" --svg section "$BOX" --z 0.5 --svg "$TMP/.svg" -o "$TMP/out.json"
bad "varieties --svg not .svg" --svg varieties "$BOX" --svg "$TMP/out.pdf" -o "$TMP/out.json"
bad "run --svg" --svg run "$BOX" --svg "$TMP/out.svg" -o "$TMP/out.step"

finish
