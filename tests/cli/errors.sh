#!/usr/bin/env bash
# Invalid input (SPEC.md, "Command line"): one check per kind of bad input. Each writes a bad spec
# into its own folder and runs `sweepvol run bad.json -o OUT.step --report R.json`; it expects exit
# code 2, stderr naming the JSON pointer of the offending field (preceded by the spec's
# line:column when the field is in the spec text), and no OUT.step left behind.
# Usage: bash tests/cli/errors.sh /path/to/sweepvol /path/to/source_dir
set -u
# shellcheck source=tests/cli/lib.sh
source "$(dirname "$0")/lib.sh"

# bad_case NAME POINTER POS [ARGS...]  (the spec text on stdin)
# POS is an extended regex for the "line:column" that must precede the pointer in the message
# ("bad.json:3:14: /entity/radius: ..."), or "-" when the error has no place in the spec text.
bad_case() {
  local name=$1 ptr=$2 pos=$3
  shift 3
  local dir="$TMP/$name"
  mkdir -p "$dir"
  cat >"$dir/bad.json"
  sv_in "$dir" run bad.json -o OUT.step --report R.json "$@"
  local ptr_re
  ptr_re=$(printf '%s' "$ptr" | sed 's/[][\.*^$+?(){}|]/\\&/g')
  if [ "$RC" -ne 2 ]; then
    fail "$name" "exit code $RC, expected 2"
  elif [ "$pos" = "-" ] && ! stderr_has " $ptr: "; then
    fail "$name" "stderr does not name the pointer '$ptr'"
  elif [ "$pos" != "-" ] && ! grep -qE -- "bad\.json:$pos: $ptr_re: " "$TMP/last.err"; then
    if stderr_has " $ptr: "; then
      fail "$name" "stderr names '$ptr' but not its line:column in bad.json"
    else
      fail "$name" "stderr does not name the pointer '$ptr' (with bad.json:line:column)"
    fi
  elif compgen -G "$dir/OUT.step*" >/dev/null; then
    fail "$name" "an output file was left behind: $(cd "$dir" && echo OUT.step*)"
  else
    pass "$name"
  fi
}

LC='[0-9]+:[0-9]+'  # any line:column

# --- the document ---------------------------------------------------------------------------------
bad_case malformed_json / '2:[0-9]+' <<'EOF'
{"sweep": 1,
 "entity": {"kind": "sphere", "center": [2, 0, 0] "radius": 1},
 "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 3, "range": [0, 6]}}
EOF

bad_case unknown_top_level_field /tolerence "$LC" <<'EOF'
{"sweep": 1,
 "tolerence": 1e-6,
 "entity": {"kind": "sphere", "center": [2, 0, 0], "radius": 1},
 "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 3, "range": [0, 6]}}
EOF

# --- kinds and fields -----------------------------------------------------------------------------
bad_case unknown_entity_kind /entity/kind "$LC" <<'EOF'
{"sweep": 1,
 "entity": {"kind": "blob", "center": [2, 0, 0], "radius": 1},
 "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 3, "range": [0, 6]}}
EOF

bad_case unknown_motion_kind /motion/kind "$LC" <<'EOF'
{"sweep": 1,
 "entity": {"kind": "sphere", "center": [2, 0, 0], "radius": 1},
 "motion": {"kind": "wobble", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 3, "range": [0, 6]}}
EOF

bad_case missing_field /entity/radius "$LC" <<'EOF'
{"sweep": 1,
 "entity": {"kind": "sphere", "center": [2, 0, 0]},
 "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 3, "range": [0, 6]}}
EOF

bad_case extra_field /entity/colour "$LC" <<'EOF'
{"sweep": 1,
 "entity": {"kind": "sphere", "center": [2, 0, 0], "radius": 1, "colour": "red"},
 "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 3, "range": [0, 6]}}
EOF

# --- numbers --------------------------------------------------------------------------------------
bad_case infinite_number /entity/radius "$LC" <<'EOF'
{"sweep": 1,
 "entity": {"kind": "sphere", "center": [2, 0, 0], "radius": 1e999},
 "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 3, "range": [0, 6]}}
EOF

bad_case negative_infinite_number /motion/range/1 "$LC" <<'EOF'
{"sweep": 1,
 "entity": {"kind": "sphere", "center": [2, 0, 0], "radius": 1},
 "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 3, "range": [0, -1e999]}}
EOF

# JSON has no NaN: the literal is a syntax error at its line:column.
bad_case nan_literal / '2:[0-9]+' <<'EOF'
{"sweep": 1,
 "entity": {"kind": "sphere", "center": [2, 0, 0], "radius": NaN},
 "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 3, "range": [0, 6]}}
EOF

bad_case nan_by_set /entity/radius - --set /entity/radius=nan <<'EOF'
{"sweep": 1,
 "entity": {"kind": "sphere", "center": [2, 0, 0], "radius": 1},
 "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 3, "range": [0, 6]}}
EOF

bad_case inverted_range /motion/joints/0/range "$LC" <<'EOF'
{"sweep": 1, "angles": "deg",
 "entity": {"kind": "sphere", "center": [2, 0, 0], "radius": 1},
 "motion": {"kind": "axes", "joints": [
   {"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": [90, 0]}]}}
EOF

bad_case empty_range /motion/joints/0/range "$LC" <<'EOF'
{"sweep": 1, "angles": "deg",
 "entity": {"kind": "sphere", "center": [2, 0, 0], "radius": 1},
 "motion": {"kind": "axes", "joints": [
   {"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": [90, 90]}]}}
EOF

bad_case zero_length_direction /motion/joints/0/direction "$LC" <<'EOF'
{"sweep": 1,
 "entity": {"kind": "sphere", "center": [0, 0, 0], "radius": 1},
 "motion": {"kind": "axes", "joints": [
   {"type": "prismatic", "direction": [0, 0, 0], "range": [0, 5]}]}}
EOF

bad_case zero_radius /entity/radius "$LC" <<'EOF'
{"sweep": 1,
 "entity": {"kind": "cylinder", "base": [2, 0, 0], "axis": [0, 0, 1], "radius": 0, "height": 1},
 "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 3, "range": [0, 6]}}
EOF

bad_case negative_radius /entity/radius "$LC" <<'EOF'
{"sweep": 1,
 "entity": {"kind": "sphere", "center": [2, 0, 0], "radius": -1},
 "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 3, "range": [0, 6]}}
EOF

# --- expressions ----------------------------------------------------------------------------------
bad_case expression_syntax_error /entity/xyz/2 "$LC" <<'EOF'
{"sweep": 1,
 "entity": {"kind": "surface", "params": {"r": [0, 1], "p": [0, 6.283185307179586]},
            "xyz": ["3+r*cos(p)", "0", "r*sin(p"]},
 "motion": {"kind": "axes", "joints": [
   {"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": [0, 1]}]}}
EOF

bad_case expression_unknown_variable /entity/xyz/0 "$LC" <<'EOF'
{"sweep": 1,
 "entity": {"kind": "surface", "params": {"r": [0, 1], "p": [0, 6.283185307179586]},
            "xyz": ["3+s*cos(p)", "0", "r*sin(p)"]},
 "motion": {"kind": "axes", "joints": [
   {"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": [0, 1]}]}}
EOF

# --- files ----------------------------------------------------------------------------------------
bad_case missing_brep_file /entity/file "$LC" <<'EOF'
{"sweep": 1,
 "entity": {"kind": "brep", "file": "nothere.step"},
 "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": [0, 0, 1], "range": [0, 3]}]}}
EOF

mkdir -p "$TMP/unreadable_step"
printf 'ISO-10303-21;\nthis is not a STEP file\n' >"$TMP/unreadable_step/x.step"
bad_case unreadable_step /entity/file "$LC" <<'EOF'
{"sweep": 1,
 "entity": {"kind": "brep", "file": "x.step"},
 "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": [0, 0, 1], "range": [0, 3]}]}}
EOF

# --- command-line options -------------------------------------------------------------------------
bad_case set_no_such_field /motion/joints/3/range - --set '/motion/joints/3/range=[0,180]' <<'EOF'
{"sweep": 1, "angles": "deg",
 "entity": {"kind": "sphere", "center": [2, 0, 0], "radius": 1},
 "motion": {"kind": "axes", "joints": [
   {"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": [0, 90]}]}}
EOF

bad_case set_not_a_pointer entity/radius - --set 'entity/radius=2' <<'EOF'
{"sweep": 1,
 "entity": {"kind": "sphere", "center": [2, 0, 0], "radius": 1},
 "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 3, "range": [0, 6]}}
EOF

# Unsupported output extension: exit 2 before any work, nothing written.
dir="$TMP/unsupported_extension"
mkdir -p "$dir"
cat >"$dir/good.json" <<'EOF'
{"sweep": 1, "angles": "deg",
 "entity": {"kind": "box", "min": [1, 0, 0], "max": [2, 1, 1]},
 "motion": {"kind": "axes", "joints": [
   {"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": [0, 90]}]}}
EOF
sv_in "$dir" run good.json -o out.xyz --report R.json
if [ "$RC" -ne 2 ]; then
  fail unsupported_extension "exit code $RC, expected 2"
elif ! stderr_has "out.xyz"; then
  fail unsupported_extension "stderr does not quote the file name"
elif compgen -G "$dir/out.xyz*" >/dev/null; then
  fail unsupported_extension "an output file was left behind"
else
  pass unsupported_extension
fi

finish
