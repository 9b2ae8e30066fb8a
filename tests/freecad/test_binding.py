"""The _sweepcore binding under /usr/bin/python3 (FreeCAD's interpreter), without FreeCAD:
specs as dicts and text, the report, BRep text out and in, and errors with the CLI's messages."""

import json
import math
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.environ["SWEEP_TEST_DIR"])
sys.path.insert(0, os.environ["SWEEP_FREECAD_LIB"])
from runner import EXAMPLES, PI, SOURCE, check, close, run  # noqa: E402

import _sweepcore as sc  # noqa: E402

SWEEPVOL = os.environ.get("SWEEPVOL", "")
BOX = os.path.join(EXAMPLES, "box_revolve_90.json")


def sphere_extrude(length):
    return {"sweep": 1, "entity": {"kind": "sphere", "center": [0, 0, 0], "radius": 1},
            "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": [0, 0, 1], "range": [0, length]}]}}


def test_run_dict():
    r = sc.run(json.load(open(BOX)))
    rep = r["report"]
    check(rep["status"] == "ok", rep)
    check(rep["sweep_report"] == 1, rep)
    close(rep["volume"]["brep"], 1 + PI, what="box revolve, B-rep")
    close(rep["volume"]["divergence"], 1 + PI, rel=1e-8, what="box revolve, divergence")
    check(r["brep"].startswith("DBRep_DrawableShape") or "CASCADE Topology" in r["brep"][:200], r["brep"][:80])
    check(r["spec"]["motion"]["kind"] == "axes", r["spec"])


def test_run_text_and_base_dir():
    text = open(BOX).read()
    rep = sc.run(text, base_dir=EXAMPLES)["report"]
    close(rep["volume"]["brep"], 1 + PI, what="box revolve from text")


def test_overrides_like_set():
    rep = sc.run(sphere_extrude(1), overrides=["/motion/joints/0/range=[0,3]"])["report"]
    close(rep["volume"]["brep"], 4 / 3 * PI + 3 * PI, rel=1e-8, what="sphere extruded 3")


def test_verify_gives_the_triad():
    rep = sc.run(sphere_extrude(2), verify=True, mc_samples=20000)["report"]
    v = rep["volume"]
    check("monte_carlo" in v and "monte_carlo_stderr" in v, v)
    exact = 4 / 3 * PI + 2 * PI
    check(abs(v["monte_carlo"] - exact) < 5 * v["monte_carlo_stderr"] + 1e-9, v)


def test_entity_brep_replaces_the_entity():
    box = sc.run(json.load(open(BOX)))["brep"]
    spec = sphere_extrude(1)
    spec["entity"] = {"kind": "brep"}
    rep = sc.run(spec, entity_brep=box)["report"]
    # the swept quarter ring, extruded 1 along z: 2x as tall, same section
    close(rep["volume"]["brep"], 2 * (1 + PI / 4 * 4), rel=1e-8, what="quarter ring extruded")


def test_entity_brep_keeps_the_placement():
    box = sc.run(json.load(open(BOX)))["brep"]
    spec = sphere_extrude(1)
    spec["entity"] = {"kind": "brep", "placement": {"translate": [0, 0, 5]}}
    rep = sc.run(spec, entity_brep=box)["report"]
    close(rep["bounding_box"]["min"][2], 5, rel=0, abs_tol=1e-6, what="z min after the placement")


def test_bad_entity_brep_is_an_input_error():
    spec = sphere_extrude(1)
    spec["entity"] = {"kind": "brep"}
    try:
        sc.run(spec, entity_brep="not a BRep")
    except sc.InputError as e:
        check(e.pointer == "/entity", e.pointer)
        check("<entity_brep>" in str(e) and "/tmp/" not in str(e), str(e))
    else:
        raise AssertionError("no InputError")


def test_input_error_attributes_and_message():
    text = '{\n  "sweep": 1,\n  "entity": {"kind": "sphere", "center": [0, 0, 0], "radius": -1},\n' \
           '  "motion": {"kind": "screw", "point": [0,0,0], "direction": [0,0,1], "pitch": 1, "range": [0, 1]}\n}\n'
    try:
        sc.run(text, source="s.json")
    except ValueError as e:  # InputError is a ValueError
        check(isinstance(e, sc.InputError), type(e))
        check(e.pointer == "/entity/radius", e.pointer)
        check(e.line == 3, e.line)
        check(str(e).startswith("s.json:3:"), str(e))
    else:
        raise AssertionError("no InputError")


def test_dict_errors_have_no_line():
    spec = sphere_extrude(1)
    spec["tolerance"] = -1
    try:
        sc.check(spec)
    except sc.InputError as e:
        check(e.line == 0 and str(e).startswith("/tolerance: "), str(e))
    else:
        raise AssertionError("no InputError")


def test_messages_are_the_clis():
    check(os.access(SWEEPVOL, os.X_OK), "SWEEPVOL not set to the sweepvol binary: '%s'" % SWEEPVOL)
    bad = [
        '{"sweep": 1, "entity": {"kind": "sphere", "center": [0,0,0], "radius": 1},\n "motion": {"kind": "axes", '
        '"joints": [{"type": "revolute", "point": [0,0,0], "direction": [0,0,0], "range": [0, 1]}]}}',
        '{"sweep": 1, "entity": {"kind": "sphere", "center": [0,0,0], "radius": 1}, "motion": {"kind": "spin"}}',
        '{"sweep": 1, "entity": {"kind": "box", "min": [0,0,0]\n, "max": [1,1,1]}, "motion": ',
        '{"sweep": 2}',
        '{"sweep": 1, "entitty": {}}',
    ]
    with tempfile.TemporaryDirectory(dir=os.environ.get("SWEEP_TEST_OUT")) as d:
        for i, text in enumerate(bad):
            path = os.path.join(d, "bad%d.json" % i)
            with open(path, "w") as f:
                f.write(text)
            p = subprocess.run([SWEEPVOL, "check", path], capture_output=True, text=True)
            check(p.returncode == 2, (p.returncode, p.stderr))
            cli = p.stderr.strip()
            check(cli.startswith("sweepvol: error: "), cli)
            try:
                sc.check(text, source=path)
            except sc.InputError as e:
                check(str(e) == cli[len("sweepvol: error: "):], "binding '%s' vs CLI '%s'" % (e, cli))
            else:
                raise AssertionError("no InputError for %s" % text)


def test_type_errors():
    for bad in (5, None, [1, 2]):
        try:
            sc.run(bad)
        except TypeError:
            pass
        else:
            raise AssertionError("no TypeError for %r" % (bad,))
    try:
        sc.run({"sweep": 1, "x": float("nan")})
    except sc.InputError as e:
        check("not JSON" in str(e), str(e))
    else:
        raise AssertionError("no InputError for NaN")


def test_failed_computation_is_a_report_not_an_exception():
    # a time limit already passed at the first step: a failed report, no exception, no solid
    r = sc.run(json.load(open(BOX)), time_limit=1e-9)
    rep = r["report"]
    check(rep["status"] == "failed", rep)
    check(rep["message"] == "stopped: the time limit of 1e-09 s was reached", rep)
    check(r["brep"] is None, rep)


def test_two_prismatic_joints():
    spec = sphere_extrude(1)
    spec["motion"]["joints"].append({"type": "prismatic", "direction": [1, 0, 0], "range": [0, 1]})
    rep = sc.run(spec)["report"]
    check(rep["status"] == "ok", rep)
    # the ball plus a unit square, by Steiner's formula
    close(rep["volume"]["brep"], 2 + 2 * PI + 4 / 3 * PI, rel=1e-6, what="two prismatic joints")


def test_cancel_from_another_thread():
    import threading
    import time
    slow = json.load(open(os.path.join(EXAMPLES, "paper", "sec4_2_curve_three_skew_revolutes.json")))
    out = {}
    worker = threading.Thread(target=lambda: out.update(sc.run(slow, base_dir=EXAMPLES)))
    start = time.monotonic()
    worker.start()
    time.sleep(1.0)
    sc.cancel()
    worker.join(60)
    check(not worker.is_alive(), "the run did not stop within 60 s of cancel()")
    rep = out["report"]
    check(rep["status"] == "failed" and rep["message"] == "stopped: cancelled", rep)
    check(out["brep"] is None, rep)
    check(time.monotonic() - start < 30, "cancel took %.1f s" % (time.monotonic() - start))
    # the next run is not affected
    rep = sc.run(json.load(open(BOX)))["report"]
    check(rep["status"] == "ok", rep)


def test_no_temporary_file_left():
    tmp = os.environ.get("TMPDIR") or "/tmp"
    before = {f for f in os.listdir(tmp) if f.startswith("sweep_entity_")}
    box = sc.run(json.load(open(BOX)))["brep"]
    spec = sphere_extrude(1)
    spec["entity"] = {"kind": "brep"}
    sc.run(spec, entity_brep=box)
    sc.check(spec, entity_brep=box)
    after = {f for f in os.listdir(tmp) if f.startswith("sweep_entity_")}
    check(after <= before, after - before)


def _worker():
    sys.path.insert(0, os.path.join(SOURCE, "freecad_addon", "sweep_freecad"))
    import worker
    return worker


def test_worker_gives_the_in_process_result():
    w = _worker()
    spec = sphere_extrude(2)
    here, there = sc.run(spec), w.call(sc, "run", spec=spec)
    check(there["report"]["status"] == "ok", there["report"])
    check(there["report"]["volume"] == here["report"]["volume"], (there["report"]["volume"], here["report"]["volume"]))
    check(there["brep"] == here["brep"], "the worker's BRep text differs")
    got = w.call(sc, "varieties", spec=spec)
    check(len(got["varieties"]) == len(sc.varieties(spec)["varieties"]), got["varieties"])


def test_worker_raises_the_cores_errors():
    w = _worker()
    try:
        w.call(sc, "run", spec='{"sweep": 1, "entity": {"kind": "sphere"}}')
        check(False, "no InputError")
    except sc.InputError as e:
        check(e.pointer == "/entity/center" and e.line == 1, (e.pointer, e.line, str(e)))


def test_worker_ends_a_step_that_never_polls():
    import time
    w = _worker()
    os.environ["SWEEP_TEST_WORKER_STALL"] = "30"  # the worker sleeps, ignoring SIGTERM
    try:
        start = time.monotonic()
        r = w.call(sc, "run", spec=sphere_extrude(1), time_limit=1)
        took = time.monotonic() - start
    finally:
        del os.environ["SWEEP_TEST_WORKER_STALL"]
    rep = r["report"]
    check(rep["status"] == "failed" and rep["message"] == "stopped: the time limit of 1 s was reached", rep)
    check(r["brep"] is None, rep)
    check(took < 2.0, "the worker ended %.2f s after its start, for a limit of 1 s" % took)


def test_worker_cancel_during_a_boolean():
    import threading
    import time
    w = _worker()
    slow = json.load(open(os.path.join(EXAMPLES, "paper", "sec4_2_curve_three_skew_revolutes.json")))
    threading.Timer(1.5, w.cancel).start()
    start = time.monotonic()
    r = w.call(sc, "run", spec=slow, base_dir=EXAMPLES)
    took = time.monotonic() - start
    check(r["report"]["status"] == "failed" and r["report"]["message"] == "stopped: cancelled", r["report"])
    check(took < 2.5, "cancel took %.2f s" % (took - 1.5))


def test_file_volume():
    brep = sc.run(json.load(open(BOX)))["brep"]
    path = os.path.join(os.environ["SWEEP_TEST_OUT"], "box.brep")
    with open(path, "w") as f:
        f.write(brep)
    close(sc.file_volume(path), 1 + PI, what="file_volume")


def test_versions_agree():
    xml = open(os.path.join(SOURCE, "freecad_addon", "package.xml")).read()
    m = re.search(r"<version>([^<]+)</version>", xml)
    check(m and m.group(1) == sc.__version__, (m and m.group(1), sc.__version__))
    check(sys.version_info[:2] == (3, 11), sys.version)
    check(math.isfinite(1.0), "")


run(globals())
