#!/usr/bin/env bash
# Stopping a run (SPEC.md, "Command line"): --time-limit and SIGINT/SIGTERM end a run as `failed`
# with exit code 3 within a second, a report whose message says why, and no output file, also when
# the step running then never polls the stop request; a bad --time-limit is an input error; a limit
# that is not reached changes nothing.
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
elif compgen -G "$TMP/*limit*" | grep -qv "limit.json"; then fail "time limit stops the run" "an output file was left behind"
elif ! "$PYTHON" -c "import sys; sys.exit(float(sys.argv[1]) > 2)" "$took"; then
  fail "time limit stops the run" "took $took s for a limit of 1 s"
else pass "time limit stops the run (in $took s)"; fi

# signal_case SIGNAL MESSAGE [STALL]: the signal sent one second into the slow run stops it within
# a second; with STALL, the worker first sleeps STALL seconds ignoring every stop signal (the test
# hook SWEEP_TEST_WORKER_STALL: a step that never polls).
signal_case() {
  SWEEP_TEST_WORKER_STALL=${3:-} "$PYTHON" - "$SWEEPVOL" "$SLOW" "$TMP/sig.step" "$TMP/sig.json" "$1" \
    >"$TMP/last.out" 2>"$TMP/last.err" <<'PY'
import signal, subprocess, sys, time
sweepvol, spec, out, report, name = sys.argv[1:]
p = subprocess.Popen([sweepvol, "run", spec, "-o", out, "--report", report],
                     stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
time.sleep(1.0)
sent = time.monotonic()
p.send_signal(getattr(signal, name))
try:
    _, err = p.communicate(timeout=60)
except subprocess.TimeoutExpired:
    p.kill()
    sys.exit("no exit within 60 s of the signal")
took = time.monotonic() - sent
sys.stderr.write(err.decode())
if took > 1.0:
    sys.exit("exit %.2f s after the signal" % took)
sys.exit(0 if p.returncode == 3 else "exit %d, expected 3" % p.returncode)
PY
  local rc=$? what="$1 stops the run${3:+ in a step that never polls}"
  if [ "$rc" -ne 0 ]; then fail "$what" "$(tail -n 1 "$TMP/last.err")"
  elif ! report_field "$TMP/sig.json" "r['message']" | grep -qF "stopped: $2"; then
    fail "$what" "message: $(report_field "$TMP/sig.json" "r['message']")"
  elif compgen -G "$TMP/*sig*" | grep -qv "sig.json"; then fail "$what" "an output file was left behind"
  else pass "$what"; fi
  rm -f "$TMP/sig.json"
}
signal_case SIGINT "interrupted (SIGINT)"
signal_case SIGTERM "terminated (SIGTERM)"
signal_case SIGTERM "terminated (SIGTERM)" 30
signal_case SIGINT "interrupted (SIGINT)" 30

# a step that never polls still ends at the time limit (plus half a second of grace)
start=$(date +%s.%N)
SWEEP_TEST_WORKER_STALL=30 sv run "$QUICK" --time-limit 1 -o "$TMP/stall.step" --report "$TMP/stall.json"
took=$("$PYTHON" -c "import sys; print(float(sys.argv[2]) - float(sys.argv[1]))" "$start" "$(date +%s.%N)")
if [ "$RC" -ne 3 ]; then fail "time limit ends a step that never polls" "exit $RC, expected 3"
elif ! report_field "$TMP/stall.json" "r['message']" | grep -q "^stopped: the time limit of 1 s was reached"; then
  fail "time limit ends a step that never polls" "message: $(report_field "$TMP/stall.json" "r['message']")"
elif compgen -G "$TMP/*stall*" | grep -qv "stall.json"; then fail "time limit ends a step that never polls" "an output file was left behind"
elif ! "$PYTHON" -c "import sys; sys.exit(float(sys.argv[1]) > 2)" "$took"; then
  fail "time limit ends a step that never polls" "took $took s for a limit of 1 s"
else pass "time limit ends a step that never polls (in $took s)"; fi

# varieties and section end the same way, with their own failed report on stdout
for cmd in varieties section; do
  extra=(); [ "$cmd" = section ] && extra=(--z 0)
  SWEEP_TEST_WORKER_STALL=30 sv "$cmd" "$QUICK" "${extra[@]}" --time-limit 1 -o "$TMP/$cmd.json"
  if [ "$RC" -ne 3 ]; then fail "$cmd ends at the time limit" "exit $RC, expected 3"
  elif ! "$PYTHON" -c "import json,sys; r=json.load(open(sys.argv[1])); sys.exit(r['status'] != 'failed' or 'time limit' not in r['message'])" "$TMP/last.out"; then
    fail "$cmd ends at the time limit" "stdout: $(head -c 200 "$TMP/last.out")"
  elif compgen -G "$TMP/*$cmd*" >/dev/null; then fail "$cmd ends at the time limit" "an output file was left behind"
  else pass "$cmd ends at the time limit"; fi
done

# the default limit is documented
sv --help
if grep -q "default 600" "$TMP/last.out"; then pass "the default time limit is documented"
else fail "the default time limit is documented" "not in --help"; fi

sv run "$QUICK" --report "$TMP/free.json"
free_rc=$RC
sv run "$QUICK" --time-limit 600 --report "$TMP/limited.json"
if [ "$free_rc" -ne 0 ] || [ "$RC" -ne 0 ]; then fail "a limit not reached changes nothing" "exit $free_rc and $RC"
elif [ "$(report_field "$TMP/free.json" "r['volume']['brep']")" != "$(report_field "$TMP/limited.json" "r['volume']['brep']")" ]; then
  fail "a limit not reached changes nothing" "volumes differ"
else pass "a limit not reached changes nothing"; fi

finish
