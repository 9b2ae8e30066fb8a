#!/usr/bin/env bash
# Stopping a run (SPEC.md, "Command line"): --time-limit and SIGINT/SIGTERM end a run as `failed`
# with exit code 3, a report whose message says why, and no output file; a bad --time-limit is an
# input error; a limit that is not reached changes nothing.
# Usage: bash tests/cli/stop.sh /path/to/sweepvol /path/to/source_dir
set -u
# shellcheck source=tests/cli/lib.sh
source "$(dirname "$0")/lib.sh"

SLOW="$SRC/examples/paper/sec4_2_curve_three_skew_revolutes.json"  # about a minute
QUICK="$SRC/examples/sphere_spring.json"

# report_field FILE EXPR: a field of a JSON report, printed by Python
report_field() { "$PYTHON" -c "import json,sys; r=json.load(open(sys.argv[1])); print($2)" "$1"; }

for bad in abc 0 -1 inf; do
  sv run "$QUICK" --time-limit "$bad"
  if [ "$RC" -eq 2 ] && stderr_has "--time-limit"; then pass "time limit '$bad' is refused"
  else fail "time limit '$bad' is refused" "exit $RC"; fi
done

start=$(date +%s.%N)
sv run "$SLOW" --time-limit 1 -o "$TMP/limit.step" --report "$TMP/limit.json"
took=$("$PYTHON" -c "import sys; print(float(sys.argv[2]) - float(sys.argv[1]))" "$start" "$(date +%s.%N)")
if [ "$RC" -ne 3 ]; then fail "time limit stops the run" "exit $RC, expected 3"
elif [ "$(report_field "$TMP/limit.json" "r['status']")" != failed ]; then fail "time limit stops the run" "status not failed"
elif ! report_field "$TMP/limit.json" "r['message']" | grep -q "^stopped: the time limit of 1 s was reached"; then
  fail "time limit stops the run" "message: $(report_field "$TMP/limit.json" "r['message']")"
elif compgen -G "$TMP/limit.step*" >/dev/null; then fail "time limit stops the run" "an output file was left behind"
elif ! "$PYTHON" -c "import sys; sys.exit(float(sys.argv[1]) > 30)" "$took"; then
  fail "time limit stops the run" "took $took s for a limit of 1 s"
else pass "time limit stops the run (in $took s)"; fi

# signal_case SIGNAL MESSAGE: the signal sent one second into the slow run stops it
signal_case() {
  "$PYTHON" - "$SWEEPVOL" "$SLOW" "$TMP/sig.step" "$TMP/sig.json" "$1" >"$TMP/last.out" 2>"$TMP/last.err" <<'PY'
import signal, subprocess, sys, time
sweepvol, spec, out, report, name = sys.argv[1:]
p = subprocess.Popen([sweepvol, "run", spec, "-o", out, "--report", report],
                     stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
time.sleep(1.0)
p.send_signal(getattr(signal, name))
try:
    _, err = p.communicate(timeout=60)
except subprocess.TimeoutExpired:
    p.kill()
    sys.exit("no exit within 60 s of the signal")
sys.stderr.write(err.decode())
sys.exit(0 if p.returncode == 3 else "exit %d, expected 3" % p.returncode)
PY
  local rc=$?
  if [ "$rc" -ne 0 ]; then fail "$1 stops the run" "$(tail -n 1 "$TMP/last.err")"
  elif ! report_field "$TMP/sig.json" "r['message']" | grep -qF "stopped: $2"; then
    fail "$1 stops the run" "message: $(report_field "$TMP/sig.json" "r['message']")"
  elif compgen -G "$TMP/sig.step*" >/dev/null; then fail "$1 stops the run" "an output file was left behind"
  else pass "$1 stops the run"; fi
  rm -f "$TMP/sig.json"
}
signal_case SIGINT "interrupted (SIGINT)"
signal_case SIGTERM "terminated (SIGTERM)"

sv run "$QUICK" --report "$TMP/free.json"
free_rc=$RC
sv run "$QUICK" --time-limit 600 --report "$TMP/limited.json"
if [ "$free_rc" -ne 0 ] || [ "$RC" -ne 0 ]; then fail "a limit not reached changes nothing" "exit $free_rc and $RC"
elif [ "$(report_field "$TMP/free.json" "r['volume']['brep']")" != "$(report_field "$TMP/limited.json" "r['volume']['brep']")" ]; then
  fail "a limit not reached changes nothing" "volumes differ"
else pass "a limit not reached changes nothing"; fi

finish
