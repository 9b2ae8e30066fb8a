#!/usr/bin/env bash
# The OCCT bridge under AddressSanitizer and UndefinedBehaviorSanitizer (clang): builds
# build-san-bridge/ (-O1, our code instrumented, OCCT as Debian ships it) and runs the bridge tests
# that take seconds there: boundary faces, sewing, STEP entities and export, entity kinds, the stop
# request, signals, trajectory membership, face merging, one stage under a joint and as a general
# motion, and the verdict (but its surface case, whose
# parameter search takes minutes there). It builds only the test files these are in
# (bridge_quick_tests, tests/CMakeLists.txt). Leak detection is off
# (OCCT keeps allocations in static maps until exit).
# Exits non-zero on any test failure or sanitizer report.
set -euo pipefail
cd "$(dirname "$0")/.."
out=build-san-bridge
CC=clang CXX=clang++ cmake -S . -B "$out" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
  -DSWEEP_SANITIZE=ON >/dev/null
cmake --build "$out" -j"$(nproc)" --target bridge_quick_tests >/dev/null
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
cd "$out"
bin/bridge_quick_tests '"Kinds*" ~"Kinds: a surface extruded*","Boundary faces*","Sewing*","Brep entity*","Stop*","Circle and torus*","Trajectory membership*","Merging faces*","Verdict*" ~"Verdict: a surface under one joint*","Sweep: STEP written*","Signals*","Section refit*","One engine*"'
echo "sanitize_bridge: no finding"
