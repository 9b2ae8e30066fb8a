# shellcheck shell=bash disable=SC2034  # SRC, RC are read by the scripts that source this file
# Shared helpers for the command-line contract tests (tests/cli/*.sh). Sourced, not a test.
#
# A test script is run as `bash script.sh /path/to/sweepvol /path/to/source_dir`; it sources this
# file, runs its checks with `pass`/`fail` (or the helpers below) and ends with `finish`, which
# prints "N passed, M failed" and returns non-zero when anything failed.

if [ $# -lt 2 ]; then
  echo "usage: bash $(basename "$0") /path/to/sweepvol /path/to/source_dir" >&2
  exit 2
fi
SWEEPVOL=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
SRC=$(cd "$2" && pwd)
if [ ! -x "$SWEEPVOL" ]; then
  echo "not an executable: $SWEEPVOL" >&2
  exit 2
fi
# Seconds allowed for one sweepvol call (the CTest timeout of a whole script is 600).
SWEEPVOL_TIMEOUT=${SWEEPVOL_TIMEOUT:-300}
PYTHON=${PYTHON:-python3}

TMP=$(mktemp -d "${TMPDIR:-/tmp}/sweep-cli.XXXXXX")
trap 'rm -rf "$TMP"' EXIT

PASSED=0
FAILED=0

pass() {
  PASSED=$((PASSED + 1))
  echo "ok   - $1"
}

# fail NAME WHY: records a failure and shows the last sweepvol call's stderr.
fail() {
  FAILED=$((FAILED + 1))
  echo "FAIL - $1: $2"
  if [ -s "$TMP/last.err" ]; then sed 's/^/       stderr: /' "$TMP/last.err" | head -n 5; fi
}

finish() {
  echo "$PASSED passed, $FAILED failed"
  [ "$FAILED" -eq 0 ]
}

# sv ARGS...: runs sweepvol in the current directory; stdout to $TMP/last.out, stderr to
# $TMP/last.err, exit code in RC.
sv() {
  RC=0
  timeout "$SWEEPVOL_TIMEOUT" "$SWEEPVOL" "$@" >"$TMP/last.out" 2>"$TMP/last.err" || RC=$?
}

# sv_in DIR ARGS...: sv with DIR as the working directory (relative paths resolve there).
sv_in() {
  local dir=$1
  shift
  RC=0
  (cd "$dir" && exec timeout "$SWEEPVOL_TIMEOUT" "$SWEEPVOL" "$@") >"$TMP/last.out" 2>"$TMP/last.err" || RC=$?
}

# stderr_has TEXT: the last call's stderr contains TEXT (fixed string).
stderr_has() { grep -qF -- "$1" "$TMP/last.err"; }

# json_get FILE EXPR: prints the Python expression EXPR evaluated with `r` = the parsed JSON file.
json_get() {
  "$PYTHON" -c 'import json, sys; r = json.load(open(sys.argv[1])); print(eval(sys.argv[2]))' "$1" "$2"
}

# rel_close A B REL: |A - B| <= REL |B|.
rel_close() {
  "$PYTHON" -c 'import sys; a, b, t = map(float, sys.argv[1:]); sys.exit(0 if abs(a - b) <= t * abs(b) else 1)' \
    "$1" "$2" "$3"
}
