"""Run by test_app.py in a fresh freecadcmd: opens $SWEEP_REOPEN_FILE, records each sweep's
shape as restored and after a forced recompute, and writes $SWEEP_TEST_OUT/reopen.json."""

import json
import os
import traceback

import FreeCAD

out = {}
try:
    doc = FreeCAD.openDocument(os.environ["SWEEP_REOPEN_FILE"])

    def state(o):
        bb = o.Shape.BoundBox
        return {"status": o.Status, "message": o.Message, "volume": o.Shape.Volume, "faces": len(o.Shape.Faces),
                "bbox": [bb.XMin, bb.YMin, bb.ZMin, bb.XMax, bb.YMax, bb.ZMax]}

    sweeps = [o for o in doc.Objects if hasattr(o, "Proxy") and type(o.Proxy).__name__ == "SweepFeature"]
    for o in sweeps:
        out[o.Name] = {"restored": state(o), "expression": dict(o.ExpressionEngine).get("RangeHi0", "")}
    for o in sweeps:
        o.touch()
    doc.recompute()
    for o in sweeps:
        out[o.Name]["recomputed"] = state(o)
except Exception:
    out["error"] = traceback.format_exc()
with open(os.path.join(os.environ["SWEEP_TEST_OUT"], "reopen.json"), "w") as f:
    json.dump(out, f, indent=1)
