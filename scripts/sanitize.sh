#!/usr/bin/env bash
# The core under AddressSanitizer and UndefinedBehaviorSanitizer (clang): builds build-san/, runs
# the core tests there (but the two slow volume integrations), then fuzzes the spec and expression parsers for SECONDS each (default 60).
# Exits non-zero on any test failure, sanitizer report or fuzzer crash.
# Usage: scripts/sanitize.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
out=build-san
CC=clang CXX=clang++ cmake -S . -B "$out" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSWEEP_BUILD_OCCT=OFF \
  -DSWEEP_SANITIZE=ON -DSWEEP_FUZZ=ON >/dev/null
cmake --build "$out" -j"$(nproc)" --target core_tests fuzz_spec fuzz_expr >/dev/null
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# every core test but the two volume integrations, which take minutes under the sanitizers
"$out/bin/core_tests" '~"Orbit volume*" ~"Monte Carlo membership*"'
# seed corpora: the project's specs and a few expressions; new inputs go to a scratch copy
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/spec" "$work/expr"
cp examples/*.json examples/paper/*.json "$work/spec/"
cp tests/fuzz/corpus_expr/* "$work/expr/"
for t in spec expr; do
  "$out/bin/fuzz_$t" -max_total_time="$seconds" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$out/fuzz_$t-" -print_final_stats=1 "$work/$t" 2>&1 | tail -12
  test "${PIPESTATUS[0]}" -eq 0
done
echo "sanitize: core tests and ${seconds} s of fuzzing per parser, no finding"
