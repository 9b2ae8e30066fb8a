#!/usr/bin/env bash
# The command line of SPEC.md: help, version, unknown command, `check` on every example, and `run`
# on examples/box_revolve_90.json with every output format, the report and a --set variation.
# Usage: bash tests/cli/basics.sh /path/to/sweepvol /path/to/source_dir
set -u
# shellcheck source=tests/cli/lib.sh
source "$(dirname "$0")/lib.sh"

# --- help, version, unknown command ---------------------------------------------------------------
sv --help
if [ "$RC" -eq 0 ] && grep -q "usage" "$TMP/last.out"; then pass "--help"; else fail "--help" "exit $RC"; fi

sv --version
project_version=$(sed -n 's/^project([^)]*VERSION \([0-9][0-9.]*\).*/\1/p' "$SRC/CMakeLists.txt")
if [ "$RC" -ne 0 ]; then
  fail "--version" "exit $RC"
elif ! grep -qE '^sweepvol [0-9]+\.[0-9]+\.[0-9]+' "$TMP/last.out"; then
  fail "--version" "prints '$(head -c 80 "$TMP/last.out")'"
elif [ -n "$project_version" ] && ! grep -qF "sweepvol $project_version" "$TMP/last.out"; then
  fail "--version" "prints '$(cat "$TMP/last.out")', CMakeLists.txt says $project_version"
else
  pass "--version"
fi

sv frobnicate
if [ "$RC" -eq 2 ] && stderr_has "frobnicate"; then pass "unknown command"; else fail "unknown command" "exit $RC"; fi

sv
if [ "$RC" -eq 2 ]; then pass "no command"; else fail "no command" "exit $RC"; fi

# --- check on every example -----------------------------------------------------------------------
# brep_box_hole.json needs box_hole.step, which the tests generate: checked only when present.
for f in "$SRC"/examples/*.json "$SRC"/examples/cases/*.json; do
  [ -e "$f" ] || continue
  name=${f#"$SRC"/}
  if [ "$(basename "$f")" = brep_box_hole.json ] && [ ! -e "$(dirname "$f")/box_hole.step" ]; then
    echo "skip - check $name (box_hole.step not generated)"
    continue
  fi
  sv check "$f"
  if [ "$RC" -eq 0 ]; then pass "check $name"; else fail "check $name" "exit $RC"; fi
done

# --- run: every output format, the report ---------------------------------------------------------
EX="$SRC/examples/box_revolve_90.json"
ONE_PLUS_PI=4.141592653589793
for ext in step brep stl off; do
  out="$TMP/x.$ext"
  rep="$TMP/x_$ext.json"
  sv run "$EX" -o "$out" --report "$rep"
  if [ "$RC" -ne 0 ]; then
    fail "run -o x.$ext" "exit $RC"
  elif [ ! -s "$out" ]; then
    fail "run -o x.$ext" "no output file, or empty"
  elif compgen -G "$out.*" >/dev/null; then
    fail "run -o x.$ext" "a temporary file was left behind: $(echo "$out".*)"
  elif [ ! -s "$rep" ]; then
    fail "run -o x.$ext" "no report"
  else
    pass "run -o x.$ext"
  fi
done

rep="$TMP/x_step.json"
if [ -s "$rep" ]; then
  if status=$(json_get "$rep" 'r["sweep_report"], r["status"]') && [ "$status" = "(1, 'ok')" ]; then
    pass "report: sweep_report 1, status ok"
  else
    fail "report: sweep_report 1, status ok" "got ${status:-unparsable JSON}"
  fi
  vol=$(json_get "$rep" 'repr(r["volume"]["brep"])' 2>/dev/null)
  if [ -n "$vol" ] && rel_close "$vol" "$ONE_PLUS_PI" 1e-6; then
    pass "report: volume.brep = 1 + pi"
  else
    fail "report: volume.brep = 1 + pi" "got ${vol:-nothing}"
  fi
  # The report printed on stdout is the one written to --report.
  sv run "$EX" --report "$TMP/again.json"
  if [ "$RC" -eq 0 ] && "$PYTHON" -c '
import json, sys
a, b = json.load(open(sys.argv[1])), json.loads(open(sys.argv[2]).read())
a.pop("seconds", None); b.pop("seconds", None)
sys.exit(0 if a == b else 1)' "$TMP/again.json" "$TMP/last.out"; then
    pass "report: stdout and --report agree"
  else
    fail "report: stdout and --report agree" "exit $RC"
  fi
fi

# --- --set: a half turn instead of a quarter ------------------------------------------------------
# Every circle about z meets the section [1,2]x[0,1] in one arc, so a rotation by angle a sweeps
# area 1 + (a/2)(r_max^2 - r_min^2) = 1 + (a/2)(5 - 1): for a = pi, volume 1 + 2 pi.
ONE_PLUS_TWO_PI=7.283185307179586
rep="$TMP/half.json"
sv run "$EX" --set '/motion/joints/0/range=[0,180]' --verify --report "$rep"
if [ "$RC" -ne 0 ] || [ ! -s "$rep" ]; then
  fail "--set range=[0,180]" "exit $RC"
else
  vol=$(json_get "$rep" 'repr(r["volume"]["brep"])' 2>/dev/null)
  if [ -n "$vol" ] && rel_close "$vol" "$ONE_PLUS_TWO_PI" 1e-6; then
    pass "--set range=[0,180]: volume.brep = 1 + 2 pi"
  else
    fail "--set range=[0,180]: volume.brep = 1 + 2 pi" "got ${vol:-nothing}"
  fi
  mc=$(json_get "$rep" '"%r %r" % (r["volume"]["monte_carlo"], r["volume"]["monte_carlo_stderr"])' 2>/dev/null)
  # shellcheck disable=SC2086
  set -- $mc
  if [ $# -eq 2 ] && "$PYTHON" -c 'import sys; m, s, v = map(float, sys.argv[1:]); sys.exit(0 if 0 < s and abs(m - v) <= 4 * s else 1)' \
    "$1" "$2" "$ONE_PLUS_TWO_PI"; then
    pass "--verify: monte_carlo within 4 standard errors of 1 + 2 pi"
  else
    fail "--verify: monte_carlo within 4 standard errors of 1 + 2 pi" "got '${mc:-nothing}'"
  fi
fi

finish
