"""GUI side of the Sweep addon: view providers, commands and the task panel (needs FreeCADGui)."""
