"""Spec v1 helpers in plain Python (no FreeCAD): loading, the joints of a motion as editable
slots, and writing edited slots back. The format itself is defined in SPEC.md; the C++ core
validates it, this module only moves fields around."""

import copy
import json
import os

#: Joint types of an `axes` motion.
JOINT_TYPES = ("revolute", "prismatic", "helical")
#: Angle units of a spec (`angles`).
ANGLE_UNITS = ("deg", "rad")


def load(spec):
    """Returns (spec dict, base_dir) for a spec given as a dict, JSON text or a file path.

    base_dir is the directory relative file names in the spec are resolved against: the spec
    file's directory, or "" for a dict or text. Raises ValueError for text that is not JSON
    (the core reports finer errors on the parsed spec)."""
    if isinstance(spec, dict):
        return copy.deepcopy(spec), ""
    if not isinstance(spec, str):
        raise TypeError("spec must be a dict, JSON text or a file path, not %s" % type(spec).__name__)
    text = spec.strip()
    if text.startswith("{"):
        try:
            return json.loads(text), ""
        except ValueError as e:
            raise ValueError("spec text is not JSON: %s" % e)
    path = os.path.abspath(os.path.expanduser(spec))
    if not os.path.isfile(path):
        raise ValueError("spec file '%s' not found" % spec)
    with open(path, encoding="utf-8") as f:
        try:
            data = json.load(f)
        except ValueError as e:
            raise ValueError("%s: not JSON: %s" % (spec, e))
    if not isinstance(data, dict):
        raise ValueError("%s: a spec is a JSON object" % spec)
    return data, os.path.dirname(path)


def joint_slots(spec):
    """The joints of the spec's motion as a list of slots, outermost first.

    A slot is a dict: `pointer` (JSON pointer of the joint object), `axis` (True when the slot has
    type/point/direction/pitch: `axes`, `screw` and `polyscrew` motions), `type`, `point`,
    `direction`, `pitch`, and `range_key` (the field holding [lo, hi]: "range", or "t" for a
    path) with `lo`, `hi`. Motions without ranges (keyframes, toolpath) have no slots."""
    motion = spec.get("motion") if isinstance(spec, dict) else None
    if not isinstance(motion, dict):
        return []
    kind = motion.get("kind")
    slots = []

    def slot(pointer, node, axis, default_type, range_key="range"):
        if not isinstance(node, dict):
            return
        r = node.get(range_key)
        lo, hi = (r[0], r[1]) if isinstance(r, list) and len(r) == 2 else (0.0, 0.0)
        s = {"pointer": pointer, "axis": axis, "range_key": range_key, "lo": _num(lo), "hi": _num(hi),
             "type": node.get("type", default_type)}
        if axis:
            s["point"] = _vec(node.get("point", [0, 0, 0]))
            s["direction"] = _vec(node.get("direction", [0, 0, 1]))
            s["pitch"] = _num(node.get("pitch", 0.0))
            if kind != "axes":
                s["type"] = "helical" if s["pitch"] != 0 else "revolute"
        slots.append(s)

    if kind in ("axes", "dh"):
        for i, j in enumerate(motion.get("joints") or []):
            slot("/motion/joints/%d" % i, j, kind == "axes", "revolute")
    elif kind == "screw":
        slot("/motion", motion, True, "helical")
    elif kind == "polyscrew":
        for i, s in enumerate(motion.get("screws") or []):
            slot("/motion/screws/%d" % i, s, True, "helical")
    elif kind == "path":
        slot("/motion", motion, False, "path", "t")
    return slots


def apply_slots(spec, slots):
    """A copy of `spec` with the fields of `slots` (as from joint_slots, possibly edited)
    written back at their pointers. Slots beyond the joints of the spec are ignored: use
    axes_motion() to change the number of joints."""
    out = copy.deepcopy(spec)
    kind = out.get("motion", {}).get("kind")
    for s in slots:
        node = resolve(out, s["pointer"])
        if not isinstance(node, dict):
            continue
        node[s["range_key"]] = [s["lo"], s["hi"]]
        if not s["axis"]:
            continue
        node["direction"] = list(s["direction"])
        if kind == "axes":
            node["type"] = s["type"]
            node["point"] = list(s["point"])
            if s["type"] == "helical":
                node["pitch"] = s["pitch"]
            else:
                node.pop("pitch", None)
        else:
            node["point"] = list(s["point"])
            node["pitch"] = s["pitch"]
    return out


def axes_motion(joints):
    """An `axes` motion from joint dicts {type, point, direction, pitch?, range} (or slots)."""
    out = []
    for j in joints:
        if "range" in j:
            lo, hi = j["range"]
        else:
            lo, hi = j.get("lo", 0.0), j.get("hi", 0.0)
        t = j.get("type", "revolute")
        d = {"type": t, "point": _vec(j.get("point", [0, 0, 0])),
             "direction": _vec(j.get("direction", [0, 0, 1])), "range": [_num(lo), _num(hi)]}
        if t == "helical":
            d["pitch"] = _num(j.get("pitch", 0.0))
        out.append(d)
    return {"kind": "axes", "joints": out}


def resolve(doc, pointer):
    """The node at a JSON pointer, or None."""
    node = doc
    for tok in [t.replace("~1", "/").replace("~0", "~") for t in pointer.split("/")[1:]]:
        if isinstance(node, dict) and tok in node:
            node = node[tok]
        elif isinstance(node, list) and tok.isdigit() and int(tok) < len(node):
            node = node[int(tok)]
        else:
            return None
    return node


def _num(v):
    return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else v


def _vec(v):
    if isinstance(v, (list, tuple)) and len(v) == 3:
        return [_num(x) for x in v]
    try:  # FreeCAD.Vector
        return [float(v.x), float(v.y), float(v.z)]
    except AttributeError:
        return v
