"""Where the workbench's icons and presets are: Mod/LatticeWorkbench/Resources, beside this package (FreeCAD reads
package.xml's icon relative to the Mod folder, so checkout and install share this layout)."""
import os

# realpath: the Mod folder may be a symlink to a checkout. This file is Mod/LatticeWorkbench/latticewb/utils/.
_RESOURCES = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__)))), "Resources")


def resource_dir():
    return _RESOURCES


def icon(name):
    """Path of the SVG icon `name` (without extension)."""
    return os.path.join(_RESOURCES, "icons", name + ".svg")
