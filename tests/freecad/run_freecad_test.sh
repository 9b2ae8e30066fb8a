#!/usr/bin/env bash
# Runs one FreeCAD addon test in a private FreeCAD user home, and fails unless the test wrote a
# result line "N passed, 0 failed" (freecadcmd exits 0 even when a script raises).
#
# usage: run_freecad_test.sh MODE ADDON_DIR LIB_DIR WORK_DIR SCRIPT
#   MODE   app: freecadcmd SCRIPT; gui: freecad SCRIPT under xvfb-run (exit 77, skipped, when
#          xvfb-run is missing); python: /usr/bin/python3 SCRIPT (the interpreter FreeCAD embeds)
#   WORK_DIR is emptied and holds the user home (WORK_DIR/home, with Mod/Sweep -> ADDON_DIR and
#          Mod/SweepLib -> LIB_DIR) and the test's outputs (SWEEP_TEST_OUT).
set -uo pipefail
if [ $# -ne 5 ]; then
  echo "usage: $0 MODE ADDON_DIR LIB_DIR WORK_DIR SCRIPT" >&2
  exit 2
fi
mode=$1 addon=$2 lib=$3 work=$4 script=$5
case "$work" in
  /*/*) ;;
  *) echo "WORK_DIR must be an absolute path below a directory (got '$work')" >&2; exit 2 ;;
esac

if [ "$mode" = gui ] && ! command -v xvfb-run >/dev/null 2>&1; then
  echo "xvfb-run not found: GUI smoke test skipped"
  exit 77
fi

rm -rf -- "$work"
mkdir -p "$work/home/Mod"
ln -s "$addon" "$work/home/Mod/Sweep"
ln -s "$lib" "$work/home/Mod/SweepLib"
# A private temporary directory, so tests that look for leftover temporary files do not see
# those of tests running at the same time.
mkdir -p "$work/tmp"
export TMPDIR="$work/tmp"
export FREECAD_USER_HOME="$work/home" SWEEP_TEST_OUT="$work" PYTHONDONTWRITEBYTECODE=1
export SWEEP_FREECAD_LIB="$lib" QTWEBENGINE_DISABLE_SANDBOX=1
SWEEP_TEST_DIR=$(cd "$(dirname "$script")" && pwd)
export SWEEP_TEST_DIR
script="$SWEEP_TEST_DIR/$(basename "$script")"
result="$work/result.txt"
cd "$work"

case "$mode" in
  app) timeout 900 freecadcmd "$script"; rc=$? ;;
  gui) timeout 300 xvfb-run -a -s "-screen 0 1280x1024x24" freecad "$script"; rc=$? ;;
  python) timeout 900 /usr/bin/python3 "$script"; rc=$? ;;
  *) echo "unknown mode '$mode'" >&2; exit 2 ;;
esac

if [ ! -s "$result" ]; then
  echo "FAIL: the test wrote no result (exit code $rc): it did not run to the end" >&2
  exit 1
fi
echo "result: $(cat "$result") (exit code $rc)"
if [ $rc -ne 0 ] || ! grep -q ' 0 failed' "$result"; then
  exit 1
fi
exit 0
