# Sweep addon, application side: runs at FreeCAD start-up, also without the GUI (freecadcmd).
# Nothing to register here; the scripting API is `import sweep_freecad`.
