"""The Sweep feature (app side: importable without the GUI) and the scripting API.

A Sweep is a Part::FeaturePython whose Shape is the solid swept by an entity under a motion,
computed by the C++ core (_sweepcore). The spec v1 JSON is kept in the `Spec` property; the joints
(type, axis, pitch, range), the angle unit and the tolerance are ordinary properties that
expressions can drive, and they override the spec's fields. The report v1 comes back as
read-only properties (Status, Message, VolumeBrep, VolumeDivergence, ...).
"""

import json
import math
import os

import FreeCAD
import Part

from . import spec as specmod
from . import worker
from .native import core

#: Values of the Status property.
STATUS_OK, STATUS_FAILED, STATUS_INVALID, STATUS_ERROR = "ok", "failed", "invalid", "error"

_PROP_READONLY, _PROP_OUTPUT = 1, 8

#: Read-only report properties: (type, name, doc).
REPORT_PROPERTIES = (
    ("App::PropertyString", "Status",
     "ok; failed (the computation failed or its result did not validate); invalid (input error); "
     "error (the core could not run)"),
    ("App::PropertyString", "Message", "Why the status is not ok"),
    ("App::PropertyFloat", "VolumeBrep", "Volume of the solid (OCCT GProp)"),
    ("App::PropertyFloat", "VolumeDivergence", "Volume by the divergence theorem over the boundary patches"),
    ("App::PropertyFloat", "VolumeMonteCarlo", "Monte Carlo volume (0 unless Verify is true)"),
    ("App::PropertyFloat", "VolumeMonteCarloStdErr", "Standard error of the Monte Carlo volume"),
    ("App::PropertyFloat", "Area", "Surface area of the solid"),
    ("App::PropertyBool", "Valid", "The solid passed BRepCheck"),
    ("App::PropertyBool", "Closed", "The solid's shells are closed"),
    ("App::PropertyInteger", "Faces", "Number of faces of the solid"),
    ("App::PropertyFloat", "ToleranceAchieved", "Largest geometric tolerance of the result"),
    ("App::PropertyFloat", "Seconds", "Computation time"),
    ("App::PropertyString", "Report", "The full report v1 (JSON)"),
)

#: Per-joint properties, by index i: name pattern, type, doc, whether only axis joints have it.
JOINT_PROPERTIES = (
    ("Joint{}Type", "App::PropertyEnumeration", "Joint type (axes motions)", True),
    ("Joint{}Point", "App::PropertyVector", "A point of the joint axis, world coordinates at rest", True),
    ("Joint{}Direction", "App::PropertyVector", "Direction of the joint axis", True),
    ("Joint{}Pitch", "App::PropertyFloat", "Helical joints: length per turn", True),
    ("RangeLo{}", "App::PropertyFloat", "Lower end of the joint range (angles in the Angles unit)", False),
    ("RangeHi{}", "App::PropertyFloat", "Upper end of the joint range (angles in the Angles unit)", False),
)


class SweepInputError(ValueError):
    """Invalid sweep input, with the offending property named when there is one."""


def _group(i):
    return "Joint %d" % i


class SweepFeature:
    """Proxy of a Sweep object."""

    def __init__(self, obj, spec=None, base_dir=""):
        obj.Proxy = self
        self._syncing = False
        obj.addProperty("App::PropertyString", "Spec", "Sweep",
                        "The spec v1 (JSON). The joint, range, Angles and Tolerance properties override its "
                        "fields; Entity, when set, replaces its entity")
        obj.addProperty("App::PropertyPath", "BaseDir", "Sweep",
                        "Directory that relative file names in Spec are resolved against "
                        "(empty: the document's directory)")
        obj.addProperty("App::PropertyLinkGlobal", "Entity", "Sweep",
                        "Object whose shape, in its global placement, is the swept entity (optional)")
        obj.addProperty("App::PropertyEnumeration", "Angles", "Sweep", "Unit of the angle ranges")
        obj.Angles = list(specmod.ANGLE_UNITS)
        obj.addProperty("App::PropertyFloat", "Tolerance", "Sweep",
                        "Requested geometric tolerance in model units (0: 1e-6 times the model size)")
        obj.addProperty("App::PropertyBool", "Verify", "Sweep", "Also compute the Monte Carlo volume")
        _add_time_limit(obj)
        obj.addProperty("App::PropertyInteger", "JointCount", "Sweep", "Number of joints", _PROP_OUTPUT, True)
        for typ, name, doc in REPORT_PROPERTIES:
            obj.addProperty(typ, name, "Report", doc, _PROP_OUTPUT | _PROP_READONLY, True)
        obj.BaseDir = base_dir or ""
        if spec is not None:
            self.set_spec(obj, spec)

    # -- persistence: the proxy holds no state (FreeCAD 0.20 uses __getstate__, 0.21+ dumps)
    def __getstate__(self):
        return None

    def __setstate__(self, state):
        self._syncing = False

    def dumps(self):
        return None

    def loads(self, state):
        self._syncing = False

    def onDocumentRestored(self, obj):
        self._syncing = False
        _add_time_limit(obj)  # documents saved before the property existed
        if FreeCAD.GuiUp:  # a document saved without the GUI has no view provider proxy
            from .gui import view_provider
            view_provider.attach_to(obj)

    # -- spec <-> properties
    def set_spec(self, obj, spec):
        """Stores `spec` (a dict) and makes the joint, Angles and Tolerance properties match it."""
        self._syncing = True
        try:
            obj.Spec = json.dumps(spec, indent=1)
            _sync_properties(obj, spec)
        finally:
            self._syncing = False

    def onChanged(self, obj, prop):
        if prop != "Spec" or getattr(self, "_syncing", False) or _restoring(obj):
            return
        try:
            spec = json.loads(obj.Spec)
        except ValueError:
            return  # execute() reports it
        if isinstance(spec, dict):
            self._syncing = True
            try:
                _sync_properties(obj, spec)
            finally:
                self._syncing = False

    def execute(self, obj):
        pl = obj.Placement
        where, failure = {}, None
        try:
            spec, base_dir, where = compose(obj)
            entity = None
            if obj.Entity is not None:
                entity = global_shape(obj.Entity).exportBrepToString()
            result = compute("run", obj, spec=spec, base_dir=base_dir, entity_brep=entity, verify=obj.Verify)
        except Exception as e:  # every failure becomes Status/Message, and the object is marked
            failure = _classify(e, where)
        if failure is not None:
            status, message = failure
            _set_report(obj, None, status, message)
            obj.Shape = Part.Shape()
            raise SweepInputError(message) if status == STATUS_INVALID else RuntimeError(message)
        report = result["report"]
        _set_report(obj, report)
        if result["brep"] is None:
            obj.Shape = Part.Shape()
            raise RuntimeError("sweep failed: " + (report.get("message") or "no solid"))
        shape = Part.Shape()
        shape.importBrepFromString(result["brep"])
        obj.Shape = shape
        obj.Placement = pl


def _add_time_limit(obj):
    if "TimeLimit" not in obj.PropertiesList:
        obj.addProperty("App::PropertyFloat", "TimeLimit", "Sweep",
                        "Seconds a computation may take before it is stopped as failed (0: %g)"
                        % worker.DEFAULT_TIME_LIMIT)


def _idle():
    """Lets the GUI repaint while a worker computes (user input waits: no recompute re-enters)."""
    from PySide import QtCore, QtGui
    QtGui.QApplication.processEvents(QtCore.QEventLoop.ExcludeUserInputEvents)


def compute(fn, obj=None, time_limit=None, **kwargs):
    """Calls the core's `fn` (run, varieties) in a worker process (worker.py): it ends within the
    time limit (obj.TimeLimit, else the default) whatever step it is in, and the GUI keeps
    repainting meanwhile."""
    if time_limit is None and obj is not None and getattr(obj, "TimeLimit", 0) > 0:
        time_limit = obj.TimeLimit
    return worker.call(core(), fn, time_limit=time_limit, idle=_idle if FreeCAD.GuiUp else None, **kwargs)


def _restoring(obj):
    try:
        return "Restore" in obj.State or bool(getattr(obj.Document, "Restoring", False))
    except Exception:
        return False


def _sync_properties(obj, spec):
    """Makes the joint properties, Angles and Tolerance match the dict `spec`."""
    slots = specmod.joint_slots(spec)
    old = obj.JointCount
    for i, s in enumerate(slots):
        for pattern, typ, doc, axis_only in JOINT_PROPERTIES:
            name = pattern.format(i)
            present = name in obj.PropertiesList
            if axis_only and not s["axis"]:
                if present:
                    obj.removeProperty(name)
                continue
            if not present:
                obj.addProperty(typ, name, _group(i), doc)
                if typ == "App::PropertyEnumeration":
                    setattr(obj, name, list(specmod.JOINT_TYPES))
        if s["axis"]:
            setattr(obj, "Joint%dType" % i, s["type"] if s["type"] in specmod.JOINT_TYPES else "revolute")
            # the type of a screw or polyscrew stage follows from its pitch
            obj.setEditorMode("Joint%dType" % i, 0 if spec["motion"].get("kind") == "axes" else 1)
            setattr(obj, "Joint%dPoint" % i, FreeCAD.Vector(*_floats(s["point"])))
            setattr(obj, "Joint%dDirection" % i, FreeCAD.Vector(*_floats(s["direction"])))
            setattr(obj, "Joint%dPitch" % i, _float(s["pitch"]))
        setattr(obj, "RangeLo%d" % i, _float(s["lo"]))
        setattr(obj, "RangeHi%d" % i, _float(s["hi"]))
    for i in range(len(slots), max(old, len(slots))):
        for pattern, _, _, _ in JOINT_PROPERTIES:
            if pattern.format(i) in obj.PropertiesList:
                obj.removeProperty(pattern.format(i))
    obj.JointCount = len(slots)
    obj.Angles = spec.get("angles", "rad") if spec.get("angles", "rad") in specmod.ANGLE_UNITS else "rad"
    tol = spec.get("tolerance", 0.0)
    obj.Tolerance = _float(tol)


def _float(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return 0.0


def _floats(v):
    return [_float(x) for x in v] if isinstance(v, (list, tuple)) and len(v) == 3 else [0.0, 0.0, 1.0]


def compose(obj):
    """The spec the feature computes: Spec with the property values written in.

    Returns (spec dict, base_dir, {JSON pointer: property name})."""
    try:
        spec = json.loads(obj.Spec or "{}")
    except ValueError as e:
        raise SweepInputError("Spec: not JSON: %s" % e)
    if not isinstance(spec, dict):
        raise SweepInputError("Spec: a spec is a JSON object")
    where = {"/tolerance": "Tolerance", "/angles": "Angles"}
    slots = specmod.joint_slots(spec)
    for i, s in enumerate(slots[:obj.JointCount]):
        s["lo"] = _finite(obj, "RangeLo%d" % i)
        s["hi"] = _finite(obj, "RangeHi%d" % i)
        where[s["pointer"] + "/" + s["range_key"]] = "RangeLo%d/RangeHi%d" % (i, i)
        if s["axis"]:
            s["type"] = getattr(obj, "Joint%dType" % i)
            s["point"] = _finite(obj, "Joint%dPoint" % i)
            s["direction"] = _finite(obj, "Joint%dDirection" % i)
            s["pitch"] = _finite(obj, "Joint%dPitch" % i)
            for field in ("type", "point", "direction", "pitch"):
                where["%s/%s" % (s["pointer"], field)] = "Joint%d%s" % (i, field.capitalize())
    spec = specmod.apply_slots(spec, slots[:obj.JointCount])
    spec["angles"] = obj.Angles
    tolerance = _finite(obj, "Tolerance")
    if tolerance == 0:
        spec.pop("tolerance", None)
    else:
        spec["tolerance"] = tolerance  # a negative one is reported by the core
    if obj.Entity is not None:
        where["/entity"] = "Entity"
        spec["entity"] = {"kind": "brep"}  # replaced by the entity's shape (entity_brep)
    base_dir = obj.BaseDir
    if not base_dir and obj.Document.FileName:
        base_dir = os.path.dirname(obj.Document.FileName)
    return spec, base_dir, where


def _finite(obj, prop):
    """The value of a float or vector property (a vector as a list); SweepInputError naming the
    property when it is not finite (JSON has no inf or nan)."""
    value = getattr(obj, prop)
    values = specmod._vec(value) if isinstance(value, FreeCAD.Vector) else value
    for x in values if isinstance(values, list) else [values]:
        if not math.isfinite(x):
            raise SweepInputError("%s: must be a finite number (got %s)" % (prop, value))
    return values


def global_shape(entity):
    """The shape of a FreeCAD object in its global placement (through App::Part containers)."""
    if not hasattr(entity, "isDerivedFrom"):
        raise TypeError("the entity must be a FreeCAD document object, not %s" % type(entity).__name__)
    shape = Part.getShape(entity)
    if shape.isNull():
        raise SweepInputError("Entity: '%s' has no shape" % entity.Label)
    parent = entity.getParentGeoFeatureGroup()
    if parent is not None:
        shape = shape.copy()
        shape.Placement = parent.getGlobalPlacement().multiply(shape.Placement)
    return shape


def _classify(e, where):
    """(status, message) for an exception raised while preparing or running a sweep."""
    try:
        input_error = core().InputError
    except ImportError:
        input_error = ()
    if input_error and isinstance(e, input_error):
        return STATUS_INVALID, _message_for_pointer(str(e), getattr(e, "pointer", ""), where)
    if isinstance(e, (SweepInputError, TypeError)):
        return STATUS_INVALID, str(e)
    return STATUS_ERROR, "%s: %s" % (type(e).__name__, e)


def _message_for_pointer(message, pointer, where):
    """Names the property behind a JSON pointer: 'Tolerance (/tolerance): must be positive'."""
    best = ""
    for p in where:
        if (pointer == p or pointer.startswith(p + "/")) and len(p) > len(best):
            best = p
    if not best:
        return message
    text = message[len(pointer) + 2:] if message.startswith(pointer + ": ") else message
    return "%s (%s): %s" % (where[best], pointer, text)


def _set_report(obj, report, status=None, message=""):
    report = report or {}
    vol = report.get("volume", {})
    obj.Status = status or report.get("status", STATUS_FAILED)
    obj.Message = message if status else report.get("message", "")
    obj.VolumeBrep = vol.get("brep", 0.0)
    obj.VolumeDivergence = vol.get("divergence", 0.0)
    obj.VolumeMonteCarlo = vol.get("monte_carlo", 0.0)
    obj.VolumeMonteCarloStdErr = vol.get("monte_carlo_stderr", 0.0)
    obj.Area = report.get("area", 0.0)
    obj.Valid = bool(report.get("valid", False))
    obj.Closed = bool(report.get("closed", False))
    obj.Faces = int(report.get("faces", 0))
    obj.ToleranceAchieved = report.get("tolerance", {}).get("achieved", 0.0)
    obj.Seconds = report.get("seconds", {}).get("total", 0.0)
    obj.Report = json.dumps(report, indent=1, sort_keys=True) if report else ""


def is_sweep(obj):
    """True for a Sweep feature."""
    return obj is not None and isinstance(getattr(obj, "Proxy", None), SweepFeature)


# ---------------------------------------------------------------------------------------------
# Scripting API


def make_sweep(doc, spec=None, entity=None, joints=None, angles=None, tolerance=None, verify=False,
               name="Sweep", recompute=True):
    """Adds a Sweep to `doc` and returns it.

    spec: a spec v1 dict, JSON text or file path (relative file names resolve against the file's
    directory). entity: a FreeCAD object whose shape (in its global placement) is the entity,
    replacing the spec's. joints: axes joints, outermost first, each
    {"type": "revolute"|"prismatic"|"helical", "point": [x,y,z], "direction": [x,y,z],
    "pitch": length per turn (helical), "range": [lo, hi]}, replacing the spec's motion.
    angles: "deg" or "rad" (the spec's default is rad). tolerance: requested tolerance (> 0).

    Raises SweepInputError or _sweepcore.InputError (a ValueError) for invalid input, before
    anything is added to the document."""
    if spec is None:
        data, base_dir = {"sweep": 1}, ""
    else:
        data, base_dir = specmod.load(spec)
    data.setdefault("sweep", 1)
    if joints is not None:
        if not isinstance(joints, (list, tuple)) or not joints:
            raise SweepInputError("joints must be a non-empty list of joint dicts")
        data["motion"] = specmod.axes_motion(joints)
    if angles is not None:
        if angles not in specmod.ANGLE_UNITS:
            raise SweepInputError("angles must be 'deg' or 'rad' (got %r)" % (angles,))
        data["angles"] = angles
    if tolerance is not None:
        data["tolerance"] = tolerance
    entity_brep = None
    if entity is not None:
        entity_brep = global_shape(entity).exportBrepToString()
        data["entity"] = {"kind": "brep"}
    if "entity" not in data:
        raise SweepInputError("the spec has no entity: give one in the spec or pass entity=<object>")
    if "motion" not in data:
        raise SweepInputError("the spec has no motion: give one in the spec or pass joints=[...]")
    core().check(data, base_dir=base_dir, entity_brep=entity_brep)

    obj = doc.addObject("Part::FeaturePython", name)
    SweepFeature(obj, data, base_dir)
    if entity is not None:
        obj.Entity = entity
    if FreeCAD.GuiUp:
        from .gui import view_provider
        view_provider.attach_to(obj)
    if recompute:
        doc.recompute()
    return obj


def set_joints(obj, joints):
    """Replaces the motion of a Sweep by the axes joints `joints` (see make_sweep)."""
    if not is_sweep(obj):
        raise TypeError("not a Sweep feature: %r" % (obj,))
    spec = json.loads(obj.Spec or "{}")
    spec["motion"] = specmod.axes_motion(joints)
    spec["angles"] = obj.Angles
    obj.Proxy.set_spec(obj, spec)


def joints(obj):
    """The joints of a Sweep as slots (see spec.joint_slots), with the property values in."""
    spec, _, _ = compose(obj)
    return specmod.joint_slots(spec)


def verify(obj, samples=None):
    """Runs the Sweep's spec with the Monte Carlo check and returns the report v1 dict (the volume
    triad is report["volume"]: brep, divergence, monte_carlo, monte_carlo_stderr). The document is
    not changed."""
    spec, base_dir, _ = compose(obj)
    entity = global_shape(obj.Entity).exportBrepToString() if obj.Entity is not None else None
    kw = {"mc_samples": int(samples)} if samples else {}
    return compute("run", obj, spec=spec, base_dir=base_dir, entity_brep=entity, verify=True, **kw)["report"]


def varieties_available():
    """True when the core computes boundary varieties."""
    return hasattr(core(), "varieties")


def make_varieties(doc, obj, name="Varieties"):
    """Adds a Part::Feature holding the boundary varieties of a Sweep (its candidate boundary
    patches). Raises NotImplementedError when the core does not compute them, RuntimeError when the
    sweep itself fails."""
    if not varieties_available():
        raise NotImplementedError("boundary varieties are not available yet in the sweep core")
    spec, base_dir, _ = compose(obj)
    entity = global_shape(obj.Entity).exportBrepToString() if obj.Entity is not None else None
    result = compute("varieties", obj, spec=spec, base_dir=base_dir, entity_brep=entity)
    if result["brep"] is None:
        raise RuntimeError("no varieties: the sweep failed: " + result["report"]["message"])
    shape = Part.Shape()
    shape.importBrepFromString(result["brep"])
    out = doc.addObject("Part::Feature", name)
    out.Shape = shape
    return out
