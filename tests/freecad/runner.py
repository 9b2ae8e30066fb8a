"""A tiny test runner for scripts run by freecadcmd, freecad or /usr/bin/python3: runs every
test_* function of a module, prints "N passed, N failed", writes that line to
$SWEEP_TEST_OUT/result.txt and exits 1 on failure (freecadcmd itself exits 0 whatever happens)."""

import math
import os
import sys
import time
import traceback

OUT = os.environ.get("SWEEP_TEST_OUT", os.getcwd())
SOURCE = os.environ.get("SWEEP_SOURCE_DIR") or os.path.abspath(
    os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
EXAMPLES = os.path.join(SOURCE, "examples")


def close(actual, expected, rel=1e-9, abs_tol=1e-12, what="value"):
    """Asserts |actual - expected| <= rel |expected| + abs_tol."""
    if not (abs(actual - expected) <= rel * abs(expected) + abs_tol):
        raise AssertionError("%s: %.15g, expected %.15g (rel. error %.3g, allowed %.3g)" % (
            what, actual, expected, abs(actual - expected) / max(abs(expected), 1e-300), rel))


def check(cond, message):
    if not cond:
        raise AssertionError(message)


def run(namespace, only=None):
    tests = [(n, f) for n, f in namespace.items() if n.startswith("test_") and callable(f)]
    tests.sort(key=lambda t: t[1].__code__.co_firstlineno)
    if only:
        tests = [t for t in tests if t[0] in only]
    passed = failed = 0
    for name, fn in tests:
        t0 = time.time()
        try:
            fn()
        except BaseException:
            failed += 1
            sys.stdout.write("FAIL %s (%.2f s)\n%s\n" % (name, time.time() - t0, traceback.format_exc()))
        else:
            passed += 1
            sys.stdout.write("ok   %s (%.2f s)\n" % (name, time.time() - t0))
        sys.stdout.flush()
    line = "%d passed, %d failed" % (passed, failed)
    if not tests:
        line = "0 passed, 1 failed (no tests found)"
        failed = 1
    sys.stdout.write(line + "\n")
    sys.stdout.flush()
    with open(os.path.join(OUT, "result.txt"), "w") as f:
        f.write(line + "\n")
    sys.exit(1 if failed else 0)


PI = math.pi
