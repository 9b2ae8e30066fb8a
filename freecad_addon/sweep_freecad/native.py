"""Finds and imports the compiled core module `_sweepcore` (built by CMake into
<build>/freecad_addon/lib, never into the addon's source tree).

Looked up, in order: on sys.path (FreeCAD puts every Mod dir entry on it, so a Mod entry linked to
<build>/freecad_addon/lib works), in the directories of the SWEEP_FREECAD_LIB environment variable,
then in build/freecad_addon/lib of the source tree the addon lives in."""

import glob
import importlib
import os
import sys

_module = None


def _candidates():
    env = os.environ.get("SWEEP_FREECAD_LIB", "")
    dirs = [d for d in env.split(os.pathsep) if d]
    addon = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
    dirs.append(os.path.join(os.path.dirname(addon), "build", "freecad_addon", "lib"))
    return dirs


def core():
    """The _sweepcore module. Raises ImportError saying where it was looked for."""
    global _module
    if _module is not None:
        return _module
    try:
        _module = importlib.import_module("_sweepcore")
        return _module
    except ImportError:
        pass
    tried = []
    for d in _candidates():
        tried.append(d)
        if glob.glob(os.path.join(d, "_sweepcore*.so")):
            if d not in sys.path:
                sys.path.insert(0, d)
            _module = importlib.import_module("_sweepcore")
            return _module
    raise ImportError(
        "the sweep core module _sweepcore was not found (looked on sys.path and in %s). Build the project "
        "with SWEEP_BUILD_PYTHON=ON, then link <build>/freecad_addon/lib into the FreeCAD Mod directory "
        "(e.g. Mod/SweepLib) or set SWEEP_FREECAD_LIB to it." % ", ".join(tried))
