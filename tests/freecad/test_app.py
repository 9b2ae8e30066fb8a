"""The Sweep feature under freecadcmd: features from a spec and from FreeCAD objects, exact
volumes, save and reopen in a fresh process, expressions from a spreadsheet, STEP export,
errors in properties, undo."""

import json
import os
import subprocess
import sys

sys.path.insert(0, os.environ["SWEEP_TEST_DIR"])
from runner import EXAMPLES, OUT, PI, check, close, run  # noqa: E402

import FreeCAD  # noqa: E402
import Part  # noqa: E402

import sweep_freecad  # noqa: E402

BOX_SPEC = os.path.join(EXAMPLES, "box_revolve_90.json")
QUARTER = 1 + PI  # box [1,2]x[0,1]x[0,1] revolved 90 degrees about z
REVOLVE_Z = [{"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": [0, 90]}]


def new_doc(name):
    return FreeCAD.newDocument(name)


def unit_box(doc, at, name="Box"):
    b = doc.addObject("Part::Box", name)
    b.Length = b.Width = b.Height = 1
    b.Placement.Base = FreeCAD.Vector(*at)
    doc.recompute()
    return b


def sphere_extrude_spec(length):
    return {"sweep": 1, "name": "unit sphere along z",
            "entity": {"kind": "sphere", "center": [0, 0, 0], "radius": 1},
            "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": [0, 0, 1], "range": [0, length]}]}}


def assert_ok(obj, volume, rel=1e-9):
    check(obj.Status == "ok", "%s: status %s: %s" % (obj.Label, obj.Status, obj.Message))
    check(obj.isValid(), obj.getStatusString())
    check(obj.Shape.isValid() and obj.Shape.Solids, "%s: no valid solid" % obj.Label)
    close(obj.Shape.Volume, volume, rel=rel, what="%s Shape.Volume" % obj.Label)
    close(obj.VolumeBrep, volume, rel=rel, what="%s VolumeBrep" % obj.Label)
    close(obj.VolumeDivergence, volume, rel=max(rel, 1e-8), what="%s VolumeDivergence" % obj.Label)


def test_feature_from_spec_file():
    doc = new_doc("spec_file")
    obj = sweep_freecad.make_sweep(doc, BOX_SPEC)
    assert_ok(obj, QUARTER)
    check(obj.JointCount == 1 and obj.Angles == "deg", (obj.JointCount, obj.Angles))
    check(obj.RangeLo0 == 0 and obj.RangeHi0 == 90, (obj.RangeLo0, obj.RangeHi0))
    check(obj.Joint0Type == "revolute", obj.Joint0Type)
    check(json.loads(obj.Report)["status"] == "ok", obj.Report)
    # report properties are read-only in the property editor
    check(obj.getEditorMode("VolumeBrep") == ["ReadOnly"], obj.getEditorMode("VolumeBrep"))
    FreeCAD.closeDocument(doc.Name)


def test_feature_from_dict_and_range_property():
    doc = new_doc("spec_dict")
    obj = sweep_freecad.make_sweep(doc, sphere_extrude_spec(2))
    assert_ok(obj, 4 / 3 * PI + 2 * PI)
    obj.RangeHi0 = 3
    doc.recompute()
    assert_ok(obj, 4 / 3 * PI + 3 * PI)
    FreeCAD.closeDocument(doc.Name)


def test_feature_from_part_box():
    doc = new_doc("part_box")
    box = unit_box(doc, (1, 0, 0))
    obj = sweep_freecad.make_sweep(doc, entity=box, joints=REVOLVE_Z, angles="deg")
    assert_ok(obj, QUARTER)
    check(obj.Entity == box, obj.Entity)
    # the entity follows its object
    box.Placement.Base = FreeCAD.Vector(2, 0, 0)
    doc.recompute()
    assert_ok(obj, 1 + PI / 4 * (10 - 4))  # [2,3]x[0,1]: 1 + (pi/4)(3^2 + 1 - 2^2)
    FreeCAD.closeDocument(doc.Name)


def test_entity_in_its_global_placement():
    doc = new_doc("container")
    part = doc.addObject("App::Part", "Part")
    part.Placement.Base = FreeCAD.Vector(1, 0, 0)
    box = unit_box(doc, (0, 0, 0))
    part.addObject(box)
    doc.recompute()
    obj = sweep_freecad.make_sweep(doc, entity=box, joints=REVOLVE_Z, angles="deg")
    assert_ok(obj, QUARTER)
    FreeCAD.closeDocument(doc.Name)


def test_joint_properties_drive_the_sweep():
    doc = new_doc("joint_props")
    box = unit_box(doc, (1, 0, 0))
    obj = sweep_freecad.make_sweep(doc, entity=box, joints=REVOLVE_Z, angles="deg")
    obj.Angles = "rad"
    obj.RangeHi0 = PI  # half a turn: 1 + (pi/2)(5 - 1)
    doc.recompute()
    assert_ok(obj, 1 + 2 * PI)
    obj.Joint0Type = "prismatic"
    obj.RangeHi0 = 2
    doc.recompute()
    assert_ok(obj, 3.0)  # the unit box extruded 2 along z
    FreeCAD.closeDocument(doc.Name)


def test_part_box_under_two_joints():
    # a body moved by a chain, as a robot link: its shape goes to the core as a B-rep, and the
    # verdict searches the joint box with that B-rep's distance bound
    doc = new_doc("part_box_chain")
    box = unit_box(doc, (1, 0, 0))
    joints = [{"type": "prismatic", "direction": [0, 0, 1], "range": [0, 2]}] + REVOLVE_Z
    obj = sweep_freecad.make_sweep(doc, entity=box, joints=joints, angles="deg")
    assert_ok(obj, 3 * QUARTER)  # the quarter turn's section over a height of 1 + 2
    FreeCAD.closeDocument(doc.Name)


def test_screw_spec_keeps_its_kind():
    import math
    doc = new_doc("screw")
    obj = sweep_freecad.make_sweep(doc, os.path.join(EXAMPLES, "sphere_spring.json"))
    check(obj.JointCount == 1 and obj.Joint0Type == "helical" and obj.Joint0Pitch == 3,
          (obj.JointCount, obj.Joint0Type, obj.Joint0Pitch))
    check(obj.getEditorMode("Joint0Type") == ["ReadOnly"], obj.getEditorMode("Joint0Type"))
    turn = math.hypot(2 * PI * 5, 3)  # helix length per turn at radius 5, pitch 3
    assert_ok(obj, PI * 2 * turn + 4 / 3 * PI, rel=1e-6)
    obj.RangeHi0 = 360
    doc.recompute()
    check(sweep_freecad.compose(obj)[0]["motion"]["kind"] == "screw", obj.Spec)
    assert_ok(obj, PI * turn + 4 / 3 * PI, rel=1e-6)
    FreeCAD.closeDocument(doc.Name)


def test_set_joints_adds_and_removes_properties():
    doc = new_doc("set_joints")
    obj = sweep_freecad.make_sweep(doc, sphere_extrude_spec(1))
    two = [{"type": "prismatic", "direction": [0, 0, 1], "range": [0, 1]},
           {"type": "helical", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 2, "range": [0, 1]}]
    sweep_freecad.set_joints(obj, two)
    check(obj.JointCount == 2 and "RangeHi1" in obj.PropertiesList and obj.Joint1Pitch == 2,
          obj.PropertiesList)
    check(json.loads(obj.Spec)["motion"]["joints"][1]["pitch"] == 2, obj.Spec)
    # several joints: failed with a message until chains land in the core, never a crash
    obj.Joint1Type = "prismatic"
    obj.Joint1Direction = FreeCAD.Vector(1, 0, 0)
    doc.recompute()
    check(obj.Status in ("ok", "failed"), (obj.Status, obj.Message))
    if obj.Status == "failed":
        check(obj.Message and obj.Shape.isNull() and not obj.isValid(), obj.Message)
    else:  # the ball plus a unit square, by Steiner's formula
        assert_ok(obj, 2 + 2 * PI + 4 / 3 * PI, rel=1e-6)
    sweep_freecad.set_joints(obj, two[:1])
    check(obj.JointCount == 1 and "RangeHi1" not in obj.PropertiesList, obj.PropertiesList)
    doc.recompute()
    assert_ok(obj, 4 / 3 * PI + PI)
    FreeCAD.closeDocument(doc.Name)


def test_editing_spec_resyncs_properties():
    doc = new_doc("edit_spec")
    obj = sweep_freecad.make_sweep(doc, sphere_extrude_spec(1))
    spec = json.loads(obj.Spec)
    spec["motion"]["joints"][0]["range"] = [0, 4]
    obj.Spec = json.dumps(spec)
    check(obj.RangeHi0 == 4, obj.RangeHi0)
    doc.recompute()
    assert_ok(obj, 4 / 3 * PI + 4 * PI)
    FreeCAD.closeDocument(doc.Name)


def test_save_reopen_in_a_fresh_process():
    doc = new_doc("reopen")
    box = unit_box(doc, (1, 0, 0))
    a = sweep_freecad.make_sweep(doc, entity=box, joints=REVOLVE_Z, angles="deg", name="FromBox")
    b = sweep_freecad.make_sweep(doc, sphere_extrude_spec(2), name="FromSpec")
    sheet = doc.addObject("Spreadsheet::Sheet", "Spreadsheet")
    sheet.set("A1", "2.5")
    doc.recompute()
    b.setExpression("RangeHi0", "Spreadsheet.A1")
    doc.recompute()
    assert_ok(a, QUARTER)
    assert_ok(b, 4 / 3 * PI + 2.5 * PI)
    path = os.path.join(OUT, "reopen.FCStd")
    doc.saveAs(path)
    expected = {o.Name: {"volume": o.Shape.Volume, "faces": len(o.Shape.Faces),
                         "bbox": [o.Shape.BoundBox.XMin, o.Shape.BoundBox.YMin, o.Shape.BoundBox.ZMin,
                                  o.Shape.BoundBox.XMax, o.Shape.BoundBox.YMax, o.Shape.BoundBox.ZMax]}
                for o in (a, b)}
    FreeCAD.closeDocument(doc.Name)

    child = os.path.join(os.environ["SWEEP_TEST_DIR"], "reopen_child.py")
    env = dict(os.environ, SWEEP_REOPEN_FILE=path, SWEEP_TEST_OUT=os.path.join(OUT, "reopen_child"))
    os.makedirs(env["SWEEP_TEST_OUT"], exist_ok=True)
    p = subprocess.run(["freecadcmd", child], env=env, capture_output=True, text=True, timeout=600)
    result = os.path.join(env["SWEEP_TEST_OUT"], "reopen.json")
    check(os.path.exists(result), "the child wrote nothing:\n%s\n%s" % (p.stdout[-3000:], p.stderr[-3000:]))
    got = json.load(open(result))
    check(not got.get("error"), got.get("error"))
    for name, e in expected.items():
        for when in ("restored", "recomputed"):
            g = got[name][when]
            check(g["status"] == "ok", (name, when, g))
            close(g["volume"], e["volume"], rel=1e-9, what="%s %s volume" % (name, when))
            check(g["faces"] == e["faces"], (name, when, g["faces"], e["faces"]))
            for x, y in zip(g["bbox"], e["bbox"]):
                close(x, y, rel=1e-9, abs_tol=1e-9, what="%s %s bounding box" % (name, when))
    check(got["FromSpec"]["expression"] == "Spreadsheet.A1", got["FromSpec"])


def test_spreadsheet_drives_a_range():
    doc = new_doc("sheet")
    sheet = doc.addObject("Spreadsheet::Sheet", "Spreadsheet")
    sheet.set("B1", "2")
    sheet.setAlias("B1", "length")
    doc.recompute()
    obj = sweep_freecad.make_sweep(doc, sphere_extrude_spec(1))
    obj.setExpression("RangeHi0", "Spreadsheet.length")
    doc.recompute()
    assert_ok(obj, 4 / 3 * PI + 2 * PI)
    sheet.set("B1", "5")
    doc.recompute()
    check(obj.RangeHi0 == 5, obj.RangeHi0)
    assert_ok(obj, 4 / 3 * PI + 5 * PI)
    sheet.set("B1", "0.75")
    doc.recompute()
    assert_ok(obj, 4 / 3 * PI + 0.75 * PI)
    FreeCAD.closeDocument(doc.Name)


def test_step_export_round_trip():
    import Import
    doc = new_doc("step")
    box = unit_box(doc, (1, 0, 0))
    a = sweep_freecad.make_sweep(doc, entity=box, joints=REVOLVE_Z, angles="deg")
    b = sweep_freecad.make_sweep(doc, sphere_extrude_spec(2))
    for obj, exact in ((a, QUARTER), (b, 4 / 3 * PI + 2 * PI)):
        path = os.path.join(OUT, obj.Name + ".step")
        Import.export([obj], path)
        back = Part.read(path)
        check(back.isValid() and back.Solids, "%s: STEP read back is not a valid solid" % obj.Name)
        close(back.Volume, exact, rel=1e-7, what="%s volume after STEP" % obj.Name)
        close(sweep_freecad.core().file_volume(path), exact, rel=1e-7, what="%s core file_volume" % obj.Name)
    FreeCAD.closeDocument(doc.Name)


def test_bad_property_values_are_reported():
    doc = new_doc("bad")
    obj = sweep_freecad.make_sweep(doc, sphere_extrude_spec(1))
    cases = [
        ("Tolerance", -1.0, "Tolerance"),
        ("Joint0Direction", FreeCAD.Vector(0, 0, 0), "Joint0Direction"),
        ("Joint0Type", "helical", "Joint0Pitch"),  # a helical joint needs a nonzero pitch
        ("RangeHi0", float("inf"), "RangeHi0"),
        ("Spec", "{not json", "Spec"),
    ]
    for prop, value, named in cases:
        good = getattr(obj, prop)
        setattr(obj, prop, value)
        doc.recompute()
        check(obj.Status == "invalid", (prop, obj.Status, obj.Message))
        check(obj.Message.startswith(named), (prop, obj.Message))
        check(not obj.isValid() and obj.Shape.isNull(), (prop, obj.State))
        setattr(obj, prop, good)
        doc.recompute()
        assert_ok(obj, 4 / 3 * PI + PI)
    # a range the core rejects or fails on: a clear status either way, never a crash
    obj.RangeLo0, obj.RangeHi0 = 2, 1
    doc.recompute()
    check(obj.Status in ("ok", "invalid", "failed"), obj.Status)
    check(obj.Status == "ok" or obj.Message, obj.Message)
    FreeCAD.closeDocument(doc.Name)


def test_bad_input_to_make_sweep_raises_and_adds_nothing():
    doc = new_doc("bad_make")
    box = unit_box(doc, (1, 0, 0))
    n = len(doc.Objects)
    bad_calls = [
        (lambda: sweep_freecad.make_sweep(doc, {"sweep": 1, "entity": {"kind": "sphere", "radius": 1},
                                                "motion": REVOLVE_Z}), "/entity/center"),
        (lambda: sweep_freecad.make_sweep(doc, entity=box, joints=[{"type": "twist", "direction": [0, 0, 1],
                                                                    "range": [0, 1]}]), "twist"),
        (lambda: sweep_freecad.make_sweep(doc, entity=box, joints=REVOLVE_Z, angles="grad"), "angles"),
        (lambda: sweep_freecad.make_sweep(doc, entity=box), "motion"),
        (lambda: sweep_freecad.make_sweep(doc, os.path.join(OUT, "missing.json")), "not found"),
    ]
    for call, needle in bad_calls:
        try:
            call()
        except ValueError as e:
            check(needle in str(e), "'%s' not in '%s'" % (needle, e))
        else:
            raise AssertionError("no error (expected one about %s)" % needle)
    check(len(doc.Objects) == n, [o.Name for o in doc.Objects])
    FreeCAD.closeDocument(doc.Name)


def test_undo_redo():
    doc = new_doc("undo")
    doc.UndoMode = 1
    box = unit_box(doc, (1, 0, 0))
    doc.openTransaction("Create Sweep")
    obj = sweep_freecad.make_sweep(doc, entity=box, joints=REVOLVE_Z, angles="deg")
    doc.commitTransaction()
    name = obj.Name
    doc.openTransaction("Edit")
    obj.RangeHi0 = 180
    doc.commitTransaction()
    doc.recompute()
    assert_ok(obj, 1 + 2 * PI)
    doc.undo()
    doc.recompute()
    check(obj.RangeHi0 == 90, obj.RangeHi0)
    assert_ok(obj, QUARTER)
    doc.undo()
    check(doc.getObject(name) is None, "the sweep survived undo")
    doc.redo()
    doc.recompute()
    check(doc.getObject(name) is not None, "redo did not bring the sweep back")
    assert_ok(doc.getObject(name), QUARTER)
    FreeCAD.closeDocument(doc.Name)


def test_axes_from_geometry():
    from sweep_freecad.axes import axis_of
    p, d = axis_of(Part.makeLine((1, 2, 3), (1, 2, 8)))
    check((p - FreeCAD.Vector(1, 2, 3)).Length < 1e-12 and (d - FreeCAD.Vector(0, 0, 1)).Length < 1e-12, (p, d))
    p, d = axis_of(Part.makeCircle(2, FreeCAD.Vector(1, 0, 0), FreeCAD.Vector(0, 1, 0)))
    check((p - FreeCAD.Vector(1, 0, 0)).Length < 1e-12 and abs(d.y - 1) < 1e-12, (p, d))
    cyl = Part.makeCylinder(1, 2, FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(1, 0, 0))
    face = [f for f in cyl.Faces if isinstance(f.Surface, Part.Cylinder)][0]
    p, d = axis_of(face)
    check(abs(abs(d.x) - 1) < 1e-12 and abs(p.y) < 1e-12 and abs(p.z) < 1e-12, (p, d))
    doc = new_doc("axes")
    z = [o for o in doc.addObject("App::Origin", "Origin").OriginFeatures if o.Role == "Z_Axis"][0]
    p, d = axis_of(z)
    check(p.Length < 1e-12 and (d - FreeCAD.Vector(0, 0, 1)).Length < 1e-12, (p, d))
    FreeCAD.closeDocument(doc.Name)


def test_check_volume_triad():
    doc = new_doc("triad")
    obj = sweep_freecad.make_sweep(doc, sphere_extrude_spec(2))
    rep = sweep_freecad.verify(obj, samples=50000)
    v = rep["volume"]
    exact = 4 / 3 * PI + 2 * PI
    close(v["brep"], exact, what="triad brep")
    close(v["divergence"], exact, rel=1e-8, what="triad divergence")
    check(abs(v["monte_carlo"] - exact) < 5 * v["monte_carlo_stderr"], v)
    check(not obj.Verify and obj.VolumeMonteCarlo == 0, "verify() changed the document")
    obj.Verify = True
    doc.recompute()
    check(obj.VolumeMonteCarlo > 0 and obj.VolumeMonteCarloStdErr > 0, obj.Report)
    FreeCAD.closeDocument(doc.Name)


def test_varieties_as_a_separate_object():
    doc = new_doc("varieties")
    obj = sweep_freecad.make_sweep(doc, sphere_extrude_spec(1))
    check(sweep_freecad.varieties_available(), "the core has no varieties")
    v = sweep_freecad.make_varieties(doc, obj)
    check(not v.Shape.isNull() and len(v.Shape.Faces) >= 3, "empty varieties")
    # the end spheres and the cylinder swept by the grazing circle
    types = sorted({f.Surface.__class__.__name__ for f in v.Shape.Faces})
    check("Sphere" in types and "Cylinder" in types, types)
    FreeCAD.closeDocument(doc.Name)


def test_time_limit_ends_a_recompute_that_never_polls():
    import time
    doc = new_doc("time_limit")
    obj = sweep_freecad.make_sweep(doc, sphere_extrude_spec(2))
    assert_ok(obj, 4 / 3 * PI + 2 * PI)
    check(obj.TimeLimit == 0, obj.TimeLimit)  # 0: the default limit
    obj.TimeLimit = 1
    obj.RangeHi0 = 3
    os.environ["SWEEP_TEST_WORKER_STALL"] = "30"  # the worker sleeps, ignoring stop signals
    try:
        start = time.monotonic()
        doc.recompute()
        took = time.monotonic() - start
    finally:
        del os.environ["SWEEP_TEST_WORKER_STALL"]
    check(obj.Status == "failed", (obj.Status, obj.Message))
    check("time limit of 1 s" in obj.Message, obj.Message)
    check(took < 2.5, "the recompute took %.2f s for a limit of 1 s" % took)
    obj.touch()
    doc.recompute()  # no stall: computes again
    assert_ok(obj, 4 / 3 * PI + 3 * PI)
    FreeCAD.closeDocument(doc.Name)


run(globals(), only=os.environ.get("SWEEP_TEST_ONLY", "").split(",") if os.environ.get("SWEEP_TEST_ONLY") else None)
