# Sweep addon, GUI side: the "Sweep" workbench. Runs through exec() at GUI start-up (no __file__
# here: paths come from sweep_freecad.paths). Commands are loaded when the workbench is activated.
import FreeCADGui


class SweepWorkbench(FreeCADGui.Workbench):
    from sweep_freecad import paths as _paths

    MenuText = "Sweep"
    ToolTip = "Exact swept volumes: solids swept by an entity under revolute, prismatic and helical joints"
    Icon = _paths.icon("Sweep_Workbench")
    del _paths

    def Initialize(self):
        from sweep_freecad.gui import commands

        self.appendToolbar("Sweep", commands.COMMANDS)
        self.appendMenu("Sweep", commands.COMMANDS)

    def Activated(self):
        pass

    def Deactivated(self):
        pass

    def GetClassName(self):
        return "Gui::PythonWorkbench"


FreeCADGui.addWorkbench(SweepWorkbench())
