"""Sweep workbench for FreeCAD: exact swept volumes as parametric features.

Scripting API (works headless, in freecadcmd):

    import sweep_freecad
    obj = sweep_freecad.make_sweep(doc, "examples/box_revolve_90.json")
    obj = sweep_freecad.make_sweep(doc, entity=doc.Box, joints=[
        {"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": [0, 90]}], angles="deg")
    obj.Shape.Volume, obj.Status, obj.VolumeBrep, obj.VolumeDivergence

The GUI (workbench, commands, task panel) lives in sweep_freecad.gui and is imported only by
InitGui.py.
"""

from .feature import (STATUS_ERROR, STATUS_FAILED, STATUS_INVALID, STATUS_OK, SweepFeature,
                      SweepInputError, compose, global_shape, is_sweep, joints, make_sweep, make_varieties,
                      set_joints, varieties_available, verify)
from .native import core

__all__ = ["make_sweep", "set_joints", "joints", "verify", "make_varieties", "varieties_available",
           "is_sweep", "compose", "global_shape", "core", "SweepFeature", "SweepInputError",
           "STATUS_OK", "STATUS_FAILED", "STATUS_INVALID", "STATUS_ERROR"]
