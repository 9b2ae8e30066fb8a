"""Task panel of a Sweep: add, remove and edit joints (type, axis, pitch, range), take an axis
from a selected edge, face or datum, set the angle unit and the tolerance. The edit is one
transaction, opened at the first Apply or OK (not while a command that opens the panel is still
running, where FreeCAD would fold it into the command's own): OK commits it, Cancel undoes it."""

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

from .. import feature, paths
from .. import spec as specmod
from ..axes import axis_of

COLUMNS = ("Type", "Point", "Direction", "Pitch", "Lower", "Upper")
_TYPE, _POINT, _DIR, _PITCH, _LO, _HI = range(len(COLUMNS))


_current = None


def current():
    """The open Sweep task panel, or None (for macros and tests)."""
    return _current


def _fmt(x):
    return "%.12g" % x


def _vec_text(v):
    return ", ".join(_fmt(c) for c in v)


def _parse_vec(text, what):
    parts = [p for p in text.replace(";", ",").replace(" ", ",").split(",") if p]
    try:
        v = [float(p) for p in parts]
    except ValueError:
        v = []
    if len(v) != 3:
        raise ValueError("%s: expected three numbers 'x, y, z' (got '%s')" % (what, text))
    return v


def _parse_float(text, what):
    try:
        return float(text)
    except ValueError:
        raise ValueError("%s: expected a number (got '%s')" % (what, text))


class SweepTaskPanel:
    def __init__(self, obj):
        self.obj = obj
        self.doc = obj.Document
        self.transaction = False
        try:
            spec = feature.compose(obj)[0]
        except ValueError as e:  # a Spec that is not JSON, a property that is not finite
            FreeCAD.Console.PrintWarning("%s: %s\n" % (obj.Label, e))
            spec = {}
        slots = specmod.joint_slots(spec)
        motion = spec.get("motion")
        kind = motion.get("kind") if isinstance(motion, dict) else None
        # axes and screw motions are edited as axes joints; other kinds keep their joints and
        # only their ranges are edited here
        self.full = kind in (None, "axes", "screw")
        self.form = self._build(slots)
        global _current
        _current = self

    # -- widgets
    def _build(self, slots):
        form = QtGui.QWidget()
        form.setWindowTitle("Sweep joints")
        form.setWindowIcon(QtGui.QIcon(paths.icon("Sweep_Feature")))
        lay = QtGui.QVBoxLayout(form)

        entity = self.obj.Entity.Label if self.obj.Entity is not None else "from the spec"
        lay.addWidget(QtGui.QLabel("Entity: %s" % entity))

        grid = QtGui.QGridLayout()
        grid.addWidget(QtGui.QLabel("Angles"), 0, 0)
        self.angles = QtGui.QComboBox()
        self.angles.addItems(list(specmod.ANGLE_UNITS))
        self.angles.setCurrentIndex(list(specmod.ANGLE_UNITS).index(self.obj.Angles))
        grid.addWidget(self.angles, 0, 1)
        grid.addWidget(QtGui.QLabel("Tolerance (0: default)"), 1, 0)
        self.tolerance = QtGui.QLineEdit(_fmt(self.obj.Tolerance))
        grid.addWidget(self.tolerance, 1, 1)
        lay.addLayout(grid)

        lay.addWidget(QtGui.QLabel("Joints, outermost first (axes in world coordinates at rest):"))
        self.table = QtGui.QTableWidget(0, len(COLUMNS))
        self.table.setHorizontalHeaderLabels(list(COLUMNS))
        self.table.horizontalHeader().setStretchLastSection(True)
        self.table.setSelectionBehavior(QtGui.QAbstractItemView.SelectRows)
        lay.addWidget(self.table)
        for s in slots:
            self._add_row(s)

        buttons = QtGui.QHBoxLayout()
        self.add_button = QtGui.QPushButton("Add joint")
        self.remove_button = QtGui.QPushButton("Remove joint")
        self.axis_button = QtGui.QPushButton("Axis from selection")
        self.axis_button.setToolTip("Set the selected joint's axis from a selected straight edge, circle, "
                                    "cylindrical face or datum line")
        for b in (self.add_button, self.remove_button, self.axis_button):
            buttons.addWidget(b)
        lay.addLayout(buttons)
        self.add_button.clicked.connect(self.on_add)
        self.remove_button.clicked.connect(self.on_remove)
        self.axis_button.clicked.connect(self.on_axis)
        self.add_button.setEnabled(self.full)
        self.remove_button.setEnabled(self.full)

        self.status = QtGui.QLabel()
        self.status.setWordWrap(True)
        lay.addWidget(self.status)
        self._show_status()
        return form

    def _add_row(self, s):
        r = self.table.rowCount()
        self.table.insertRow(r)
        combo = QtGui.QComboBox()
        if s.get("axis", True):
            combo.addItems(list(specmod.JOINT_TYPES))
            combo.setCurrentIndex(list(specmod.JOINT_TYPES).index(s["type"]) if s["type"] in specmod.JOINT_TYPES else 0)
        else:
            combo.addItem(str(s.get("type", "")))
            combo.setEnabled(False)
        self.table.setCellWidget(r, _TYPE, combo)
        axis = s.get("axis", True)
        cells = {_POINT: _vec_text(s.get("point", [0, 0, 0])) if axis else "",
                 _DIR: _vec_text(s.get("direction", [0, 0, 1])) if axis else "",
                 _PITCH: _fmt(s.get("pitch", 0.0)) if axis else "",
                 _LO: _fmt(s["lo"]), _HI: _fmt(s["hi"])}
        for c, text in cells.items():
            item = QtGui.QTableWidgetItem(text)
            if not axis and c in (_POINT, _DIR, _PITCH):
                item.setFlags(item.flags() & ~QtCore.Qt.ItemIsEditable)
            self.table.setItem(r, c, item)

    def _show_status(self):
        o = self.obj
        text = "Status: %s" % (o.Status or "not computed")
        if o.Status == feature.STATUS_OK:
            text += "\nVolume: %.12g (B-rep), %.12g (divergence)" % (o.VolumeBrep, o.VolumeDivergence)
        elif o.Message:
            text += "\n" + o.Message
        self.status.setText(text)

    # -- buttons
    def on_add(self):
        angle = 90.0 if self.angles.currentText() == "deg" else 1.5707963267948966
        self._add_row({"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 0.0,
                       "lo": 0.0, "hi": angle})

    def on_remove(self):
        rows = sorted({i.row() for i in self.table.selectedIndexes()} or {self.table.rowCount() - 1}, reverse=True)
        for r in rows:
            if r >= 0:
                self.table.removeRow(r)

    def on_axis(self):
        row = self.table.currentRow()
        if row < 0:
            row = self.table.rowCount() - 1
        if row < 0 or not self.table.cellWidget(row, _TYPE).isEnabled():
            return
        axis = None
        for sel in FreeCADGui.Selection.getSelectionEx():
            for sub in sel.SubObjects:
                axis = axis or axis_of(sub)
            if not sel.SubObjects:
                axis = axis or axis_of(sel.Object)
        if axis is None:
            QtGui.QMessageBox.information(self.form, "Sweep", "Select a straight edge, a circle, a cylindrical "
                                          "face or a datum line to take the axis from.")
            return
        self.table.item(row, _POINT).setText(_vec_text(axis[0]))
        self.table.item(row, _DIR).setText(_vec_text(axis[1]))

    # -- applying
    def _rows(self):
        out = []
        for r in range(self.table.rowCount()):
            n = "joint %d" % r
            j = {"type": self.table.cellWidget(r, _TYPE).currentText(),
                 "lo": _parse_float(self.table.item(r, _LO).text(), n + " lower"),
                 "hi": _parse_float(self.table.item(r, _HI).text(), n + " upper")}
            if self.table.cellWidget(r, _TYPE).isEnabled():
                j["point"] = _parse_vec(self.table.item(r, _POINT).text(), n + " point")
                j["direction"] = _parse_vec(self.table.item(r, _DIR).text(), n + " direction")
                j["pitch"] = _parse_float(self.table.item(r, _PITCH).text() or "0", n + " pitch")
            out.append(j)
        return out

    def apply(self):
        """Writes the table into the feature and recomputes. Returns False (with a message) on
        bad input."""
        try:
            rows = self._rows()
            if not rows:
                raise ValueError("a sweep needs at least one joint")
            tolerance = _parse_float(self.tolerance.text(), "tolerance")
            if not self.transaction:
                self.doc.openTransaction("Edit %s" % self.obj.Label)
                self.transaction = True
            self.obj.Angles = self.angles.currentText()
            if self.full:
                feature.set_joints(self.obj, rows)
            else:
                for i, j in enumerate(rows):
                    setattr(self.obj, "RangeLo%d" % i, j["lo"])
                    setattr(self.obj, "RangeHi%d" % i, j["hi"])
            self.obj.Tolerance = tolerance
        except ValueError as e:
            QtGui.QMessageBox.warning(self.form, "Sweep", str(e))
            return False
        self.doc.recompute()
        self._show_status()
        return True

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Apply | QtGui.QDialogButtonBox.Cancel)

    def clicked(self, button):
        if button == QtGui.QDialogButtonBox.Apply:
            self.apply()

    def accept(self):
        if not self.apply():
            return False
        if self.transaction:
            self.doc.commitTransaction()
        self._close()
        if self.obj.Status != feature.STATUS_OK:
            FreeCAD.Console.PrintWarning("%s: %s: %s\n" % (self.obj.Label, self.obj.Status, self.obj.Message))
        return True

    def reject(self):
        if self.transaction:
            self.doc.abortTransaction()
            self.doc.recompute()
        self._close()
        return True

    def _close(self):
        global _current
        if _current is self:
            _current = None
        FreeCADGui.ActiveDocument.resetEdit()
