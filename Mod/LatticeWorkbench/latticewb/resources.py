"""Where the workbench's icons and presets are: installed beside the package, or at the top of a checkout."""
import os

_HERE = os.path.dirname(os.path.abspath(__file__))
_CANDIDATES = [
    os.path.join(_HERE, os.pardir, "Resources"),                 # installed: Mod/LatticeWorkbench/Resources
    os.path.join(_HERE, os.pardir, os.pardir, os.pardir, "Resources"),  # checkout: <repo>/Resources
]


def resource_dir():
    for candidate in _CANDIDATES:
        if os.path.isdir(candidate):
            return os.path.normpath(candidate)
    return os.path.normpath(_CANDIDATES[0])


def icon(name):
    """Path of the SVG icon `name` (without extension)."""
    return os.path.join(resource_dir(), "icons", name + ".svg")
