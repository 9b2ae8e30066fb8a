"""Runs the sweep core in a worker process that the caller can always end.

The geometry kernel has steps that never poll a stop request, and a Python thread cannot be
ended, so FreeCAD hands each computation to a separate Python process running this file as a
script: the core's own time limit stops it at its next poll, and when it has not ended half a
second after the limit (or after cancel()), the process is killed and the call returns a failed
report saying why. While waiting, `idle` is called (the GUI repaints there), so a long sweep
never freezes FreeCAD's window.

This file imports nothing from FreeCAD: the worker process loads only the core module.
"""

import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

#: Seconds a computation may take when the caller gives no limit.
DEFAULT_TIME_LIMIT = 600.0
#: Seconds the worker has past its limit to stop by itself before it is killed.
GRACE = 0.5

_running = set()
_cancelled = False


def _python():
    """The interpreter for the worker: the one the core module was built for."""
    for exe in ("/usr/bin/python3", sys.executable):
        if exe and os.path.basename(exe).startswith("python") and os.access(exe, os.X_OK):
            return exe
    raise RuntimeError("no Python interpreter found to run the sweep worker")


def cancel():
    """Ends every computation in progress (each returns a failed report: "stopped: cancelled")."""
    global _cancelled
    _cancelled = True
    for proc in list(_running):
        try:
            proc.send_signal(signal.SIGTERM)
        except OSError:
            pass


def failed_result(fn, reason):
    """What `fn` returns when its worker had to be ended."""
    report = {"sweep_report": 1, "status": "failed", "message": reason,
              "volume": {"brep": 0.0, "divergence": 0.0}}
    if fn == "varieties":
        return {"report": report, "varieties": [], "brep": None}
    return {"report": report, "brep": None, "spec": None}


def call(core, fn, time_limit=None, idle=None, **kwargs):
    """Calls core.<fn>(**kwargs, time_limit=...) in a worker process and returns its result.

    `core` is the loaded _sweepcore module (its location is handed to the worker). Raises the
    core's InputError and ComputeError as the core does. `time_limit` in seconds (None: the
    default); `idle` is called about every 20 ms while the worker runs."""
    global _cancelled
    limit = DEFAULT_TIME_LIMIT if time_limit is None else float(time_limit)
    if not limit > 0:
        raise ValueError("time_limit must be a positive number of seconds")
    kwargs["time_limit"] = limit
    work = tempfile.mkdtemp(prefix="sweep-worker-")
    try:
        request, answer = os.path.join(work, "request.json"), os.path.join(work, "answer.json")
        with open(request, "w") as f:
            json.dump({"core_dir": os.path.dirname(os.path.abspath(core.__file__)), "fn": fn, "kwargs": kwargs}, f)
        _cancelled = False
        proc = subprocess.Popen([_python(), os.path.abspath(__file__), request, answer],
                                stdin=subprocess.DEVNULL)
        _running.add(proc)
        try:
            reason = _wait(proc, limit, idle)
        finally:
            _running.discard(proc)
        if reason is None and proc.returncode != 0:
            reason = "the computation ended abnormally (exit status %d)" % proc.returncode
        if reason is None and not os.path.exists(answer):
            reason = "the computation ended without an answer"
        if reason is not None:
            return failed_result(fn, reason)
        with open(answer) as f:
            out = json.load(f)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    if "result" in out:
        return out["result"]
    err = out["error"]
    if err["kind"] == "input":
        e = core.InputError(err["message"])
        e.pointer, e.line, e.column = err["pointer"], err["line"], err["column"]
        raise e
    if err["kind"] == "compute":
        raise core.ComputeError(err["message"])
    raise RuntimeError(err["message"])


def _wait(proc, limit, idle):
    """Waits for the worker; returns None when it ended by itself, else why it was killed."""
    deadline = time.monotonic() + limit + GRACE
    kill_at = None
    while proc.poll() is None:
        now = time.monotonic()
        if _cancelled and kill_at is None:
            kill_at = now + GRACE  # cancel() sent SIGTERM: the core stops at its next poll
        reason = None
        if kill_at is not None and now > kill_at:
            reason = "stopped: cancelled"
        elif now > deadline:
            reason = "stopped: the time limit of %g s was reached" % limit
        if reason is not None:
            proc.kill()
            proc.wait()
            return reason
        if idle is not None:
            idle()
        time.sleep(0.02)
    if _cancelled and proc.returncode != 0:
        return "stopped: cancelled"
    return None


def _serve(request, answer):
    """The worker: runs one request and writes the answer (or the error) as JSON."""
    stall = os.environ.get("SWEEP_TEST_WORKER_STALL")
    if stall:  # test hook: a step that never polls (stop signals are ignored while it sleeps)
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        time.sleep(float(stall))
    with open(request) as f:
        req = json.load(f)
    sys.path.insert(0, req["core_dir"])
    import _sweepcore

    # SIGTERM from cancel(): the core's own stop request ends the run at its next poll. Python runs
    # signal handlers on the main thread only, so the core runs on another one (it releases the GIL).
    signal.signal(signal.SIGTERM, lambda *_: _sweepcore.cancel())
    out = {}

    def work():
        try:
            out["result"] = getattr(_sweepcore, req["fn"])(**req["kwargs"])
        except _sweepcore.InputError as e:
            out["error"] = {"kind": "input", "message": str(e), "pointer": getattr(e, "pointer", ""),
                            "line": getattr(e, "line", 0), "column": getattr(e, "column", 0)}
        except _sweepcore.ComputeError as e:
            out["error"] = {"kind": "compute", "message": str(e)}
        except Exception as e:  # reported to the caller, which raises it
            out["error"] = {"kind": "internal", "message": "%s: %s" % (type(e).__name__, e)}

    thread = threading.Thread(target=work)
    thread.start()
    while thread.is_alive():
        thread.join(0.05)
    tmp = answer + ".partial"
    with open(tmp, "w") as f:
        json.dump(out, f)
    os.replace(tmp, answer)


if __name__ == "__main__":
    _serve(sys.argv[1], sys.argv[2])
