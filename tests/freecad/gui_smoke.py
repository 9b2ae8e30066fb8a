"""GUI smoke test, run as a macro by `freecad` under xvfb-run: activates the Sweep workbench,
creates a sweep from a selected box with the Sweep_Create command, edits it in the task panel,
undoes and redoes, and saves a screenshot to $SWEEP_TEST_OUT/freecad_screenshot.png."""

import os
import sys
import traceback

sys.path.insert(0, os.environ["SWEEP_TEST_DIR"])

import FreeCAD  # noqa: E402
import FreeCADGui  # noqa: E402
from PySide import QtCore  # noqa: E402

OUT = os.environ["SWEEP_TEST_OUT"]
PNG = os.path.join(OUT, "freecad_screenshot.png")


def steps():
    import math

    from runner import check, close

    FreeCADGui.activateWorkbench("SweepWorkbench")
    check(FreeCADGui.activeWorkbench().name() == "SweepWorkbench", FreeCADGui.activeWorkbench().name())
    for cmd in ("Sweep_Create", "Sweep_FromSpec", "Sweep_Varieties", "Sweep_Check"):
        check(cmd in FreeCADGui.listCommands(), "command %s missing" % cmd)

    doc = FreeCAD.newDocument("Smoke")
    box = doc.addObject("Part::Box", "Box")
    box.Length = box.Width = box.Height = 1
    box.Placement.Base = FreeCAD.Vector(1, 0, 0)
    doc.recompute()
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(box)

    # create from the selection: a quarter turn about z, then the task panel opens
    FreeCADGui.runCommand("Sweep_Create")
    sweeps = [o for o in doc.Objects if o.TypeId == "Part::FeaturePython"]
    check(len(sweeps) == 1, [o.Name for o in doc.Objects])
    obj = sweeps[0]
    check(obj.Status == "ok", (obj.Status, obj.Message))
    close(obj.Shape.Volume, 1 + math.pi, what="created sweep")
    check(not box.ViewObject.Visibility, "the entity was not hidden")
    check(obj.ViewObject.Proxy is not None and obj.ViewObject.Proxy.claimChildren() == [box], "tree children")

    from sweep_freecad.gui import task_panel
    panel = task_panel.current()
    check(panel is not None, "no task panel open after Sweep_Create")
    check(panel.table.rowCount() == 1, panel.table.rowCount())
    # widen the range to half a turn and apply through the panel
    panel.table.item(0, task_panel._HI).setText("180")
    check(panel.accept(), "accept failed: %s" % obj.Message)
    check(task_panel.current() is None, "task panel still open")
    close(obj.Shape.Volume, 1 + 2 * math.pi, what="edited sweep")

    # undo the edit, then the creation; redo both
    name = obj.Name
    check(doc.UndoNames[:2] == ["Edit Sweep", "Create Sweep"], doc.UndoNames)
    doc.undo()
    doc.recompute()
    close(obj.Shape.Volume, 1 + math.pi, what="after undoing the edit")
    doc.undo()
    check(doc.getObject(name) is None, "undo did not remove the sweep")
    doc.redo()
    doc.redo()
    doc.recompute()
    obj = doc.getObject(name)
    check(obj is not None, "redo did not restore the sweep")
    close(obj.Shape.Volume, 1 + 2 * math.pi, what="after redo")

    # save, close and reopen: the view provider comes back
    path = os.path.join(OUT, "smoke.FCStd")
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    doc = FreeCAD.openDocument(path)
    obj = doc.getObject(name)
    box = doc.getObject("Box")
    from sweep_freecad.gui.view_provider import ViewProviderSweep
    check(isinstance(obj.ViewObject.Proxy, ViewProviderSweep), obj.ViewObject.Proxy)
    obj.touch()
    doc.recompute()
    close(obj.Shape.Volume, 1 + 2 * math.pi, what="after reopening")

    # the check command's text
    from sweep_freecad import verify
    from sweep_freecad.gui.commands import check_text
    text = check_text(obj, verify(obj, samples=20000))
    check("Monte Carlo" in text, text)
    check("verdict:     0 of 4096 samples" in text, text)
    FreeCAD.Console.PrintMessage(text + "\n")

    # a picture: the sweep, and the box it came from
    box.ViewObject.Visibility = True
    box.ViewObject.DisplayMode = "Wireframe"
    box.ViewObject.LineColor = (0.85, 0.45, 0.0)
    box.ViewObject.LineWidth = 4
    obj.ViewObject.ShapeColor = (0.45, 0.62, 0.85)
    obj.ViewObject.Transparency = 20
    FreeCADGui.Selection.clearSelection()
    view = FreeCADGui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    view.saveImage(PNG, 800, 600, "White")
    check(os.path.getsize(PNG) > 5000, "screenshot too small")


def main():
    code = 1
    try:
        steps()
        line = "1 passed, 0 failed"
        code = 0
    except Exception:
        line = "0 passed, 1 failed"
        sys.stdout.write(traceback.format_exc())
    sys.stdout.write(line + "\n")
    sys.stdout.flush()
    with open(os.path.join(OUT, "result.txt"), "w") as f:
        f.write(line + "\n")
    os._exit(code)


QtCore.QTimer.singleShot(2000, main)
