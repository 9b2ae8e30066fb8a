"""View provider of the Sweep feature: icon, the entity as a child in the tree, and the task
panel on double click / Edit."""

import FreeCAD
import FreeCADGui

from .. import paths


class ViewProviderSweep:
    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.Object = vobj.Object

    def getIcon(self):
        return paths.icon("Sweep_Feature")

    def claimChildren(self):
        obj = getattr(self, "Object", None)
        entity = getattr(obj, "Entity", None) if obj is not None else None
        return [entity] if entity is not None else []

    def setupContextMenu(self, vobj, menu):
        action = menu.addAction("Edit joints of %s" % vobj.Object.Label)
        action.triggered.connect(lambda: self.startDefaultEditMode(vobj))
        return False

    def startDefaultEditMode(self, vobj):
        vobj.Document.setEdit(vobj.Object, 0)

    def doubleClicked(self, vobj):
        self.startDefaultEditMode(vobj)
        return True

    def setEdit(self, vobj, mode):
        if mode != 0:
            return False
        from .task_panel import SweepTaskPanel
        FreeCADGui.Control.showDialog(SweepTaskPanel(vobj.Object))
        return True

    def unsetEdit(self, vobj, mode):
        if mode != 0:
            return False
        FreeCADGui.Control.closeDialog()
        return True

    def onDelete(self, vobj, subelements):
        entity = getattr(vobj.Object, "Entity", None)
        if entity is not None and getattr(entity, "ViewObject", None) is not None:
            entity.ViewObject.Visibility = True
        return True

    # the proxy holds no state (FreeCAD 0.20 uses __getstate__, 0.21+ dumps)
    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    def dumps(self):
        return None

    def loads(self, state):
        return None


def attach_to(obj):
    """Gives a Sweep created without the GUI (or restored) its view provider."""
    if FreeCAD.GuiUp and obj.ViewObject is not None and not isinstance(obj.ViewObject.Proxy, ViewProviderSweep):
        ViewProviderSweep(obj.ViewObject)
