"""Where the addon's files are (Init.py and InitGui.py run through exec() and have no __file__)."""

import os

ADDON_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ICON_DIR = os.path.join(ADDON_DIR, "icons")


def icon(name):
    """Path of icons/<name>.svg."""
    return os.path.join(ICON_DIR, name + ".svg")
