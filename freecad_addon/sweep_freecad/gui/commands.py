"""Commands of the Sweep workbench. Each change to a document is one transaction (undoable)."""

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

from .. import feature, paths
from ..axes import axis_of


def _main_window():
    return FreeCADGui.getMainWindow()


def _selected_sweeps():
    return [o for o in FreeCADGui.Selection.getSelection() if feature.is_sweep(o)]


def _entity_and_axis():
    """The entity (first selected object with a shape) and an axis (from a selected edge, face
    or datum line) of the current selection; either may be None."""
    entity = axis = None
    for sel in FreeCADGui.Selection.getSelectionEx():
        obj = sel.Object
        subs = list(sel.SubObjects)
        for sub in subs:
            if axis is None and sub.ShapeType in ("Edge", "Face"):
                axis = axis_of(sub)
        is_datum = obj.isDerivedFrom("App::Line") or obj.TypeId in ("PartDesign::Line", "Part::Datum")
        if is_datum and axis is None:
            axis = axis_of(obj)
        elif entity is None and not is_datum and not feature.is_sweep(obj) and _has_faces(obj):
            entity = obj
    return entity, axis


def _has_faces(obj):
    shape = getattr(obj, "Shape", None)
    return shape is not None and not shape.isNull() and bool(shape.Faces)


class _Command:
    """Common parts: IsActive needs a document."""

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None


class CreateSweep(_Command):
    def GetResources(self):
        return {"Pixmap": paths.icon("Sweep_Create"), "MenuText": "Sweep from selection",
                "ToolTip": "Sweep the selected object under a revolute joint about the selected edge, face or datum "
                           "line (the z axis if none); edit the joints in the task panel"}

    def Activated(self):
        doc = FreeCAD.ActiveDocument
        entity, axis = _entity_and_axis()
        if entity is None:
            QtGui.QMessageBox.information(_main_window(), "Sweep",
                                          "Select the object to sweep (and optionally an edge, face or datum "
                                          "line for the axis).")
            return
        point, direction = axis if axis is not None else (FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(0, 0, 1))
        joint = {"type": "revolute", "point": [point.x, point.y, point.z],
                 "direction": [direction.x, direction.y, direction.z], "range": [0, 90]}
        doc.openTransaction("Create Sweep")
        try:
            obj = feature.make_sweep(doc, entity=entity, joints=[joint], angles="deg", recompute=False)
            entity.ViewObject.Visibility = False
            doc.recompute()
        except Exception as e:
            doc.abortTransaction()
            QtGui.QMessageBox.warning(_main_window(), "Sweep", str(e))
            return
        doc.commitTransaction()
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(obj)
        FreeCADGui.ActiveDocument.setEdit(obj, 0)


class SweepFromSpec(_Command):
    def GetResources(self):
        return {"Pixmap": paths.icon("Sweep_Spec"), "MenuText": "Sweep from spec file...",
                "ToolTip": "Create a sweep from a spec v1 JSON file"}

    def Activated(self):
        doc = FreeCAD.ActiveDocument
        path, _ = QtGui.QFileDialog.getOpenFileName(_main_window(), "Sweep spec", "", "Sweep spec (*.json)")
        if not path:
            return
        doc.openTransaction("Create Sweep from spec")
        try:
            feature.make_sweep(doc, path)
        except Exception as e:
            doc.abortTransaction()
            QtGui.QMessageBox.warning(_main_window(), "Sweep", str(e))
            return
        doc.commitTransaction()


class ShowVarieties(_Command):
    def GetResources(self):
        return {"Pixmap": paths.icon("Sweep_Varieties"), "MenuText": "Boundary varieties",
                "ToolTip": "Show the boundary varieties (singular sets) of the selected sweep as a separate object"}

    def IsActive(self):
        return bool(_selected_sweeps())

    def Activated(self):
        doc = FreeCAD.ActiveDocument
        if not feature.varieties_available():
            QtGui.QMessageBox.information(_main_window(), "Sweep",
                                          "Boundary varieties are not available yet in the sweep core.")
            return
        doc.openTransaction("Sweep varieties")
        try:
            for obj in _selected_sweeps():
                feature.make_varieties(doc, obj, name=obj.Name + "_Varieties")
        except Exception as e:
            doc.abortTransaction()
            QtGui.QMessageBox.warning(_main_window(), "Sweep", str(e))
            return
        doc.commitTransaction()
        doc.recompute()


class CheckSweep(_Command):
    def GetResources(self):
        return {"Pixmap": paths.icon("Sweep_Check"), "MenuText": "Check volumes",
                "ToolTip": "Show the volume triad of the selected sweeps (B-rep, divergence theorem, Monte Carlo) "
                           "and the verdict that decided their status"}

    def IsActive(self):
        return bool(_selected_sweeps())

    def Activated(self):
        lines = []
        QtGui.QApplication.setOverrideCursor(QtGui.QCursor(QtCore.Qt.WaitCursor))
        try:
            for obj in _selected_sweeps():
                try:
                    lines.append(check_text(obj, feature.verify(obj)))
                except Exception as e:
                    lines.append("%s: %s" % (obj.Label, e))
        finally:
            QtGui.QApplication.restoreOverrideCursor()
        text = "\n\n".join(lines)
        FreeCAD.Console.PrintMessage(text + "\n")
        QtGui.QMessageBox.information(_main_window(), "Sweep volumes", text)


def check_text(obj, report):
    """The volume triad of a report as text."""
    v = report.get("volume", {})
    text = "%s: %s\n  B-rep:       %.12g\n  divergence:  %.12g" % (
        obj.Label, report.get("status"), v.get("brep", 0.0), v.get("divergence", 0.0))
    if "monte_carlo" in v:
        text += "\n  Monte Carlo: %.6g +- %.2g" % (v["monte_carlo"], v.get("monte_carlo_stderr", 0.0))
    verdict = report.get("verify")
    if verdict:
        # the verdict that decided the status: the solid against a membership test that does not use it
        text += ("\n  verdict:     %d of %d samples and %d of %d boundary probes disagree with %s;"
                 "\n               symmetric difference below %.3g (95 %%)") % (
            verdict.get("mismatches", 0), verdict.get("samples", 0), verdict.get("probe_mismatches", 0),
            verdict.get("probes", 0), verdict.get("membership", "the independent membership"),
            verdict.get("difference_bound", 0.0))
    if report.get("message"):
        text += "\n  " + report["message"]
    return text


#: Command names, in toolbar order.
COMMANDS = ["Sweep_Create", "Sweep_FromSpec", "Sweep_Varieties", "Sweep_Check"]

FreeCADGui.addCommand("Sweep_Create", CreateSweep())
FreeCADGui.addCommand("Sweep_FromSpec", SweepFromSpec())
FreeCADGui.addCommand("Sweep_Varieties", ShowVarieties())
FreeCADGui.addCommand("Sweep_Check", CheckSweep())
