"""What the FreeCAD figure scripts share: this checkout's module and workbench first on the path (not a copy
FreeCAD loaded at start), the view saved as a palette PNG (a third of the bytes, no visible change), and the run
that quits FreeCAD after drawing."""
import os
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def use_checkout(*folders):
    """build/python and the given folders of the repository first on sys.path, and any loaded copy forgotten."""
    for folder in ("build/python",) + folders:
        sys.path.insert(0, os.path.join(ROOT, folder))
    for name in [n for n in sys.modules if n.split(".")[0] in ("latticewb", "steadylattice")]:
        del sys.modules[name]


def save_view(path, width=1200, height=900):
    """The active view, isometric and fitted, as a palette PNG at `path`."""
    import FreeCADGui
    view = FreeCADGui.activeDocument().activeView()
    view.viewIsometric()
    view.fitAll()
    FreeCADGui.updateGui()
    view.saveImage(path, width, height, "White")
    from PIL import Image
    Image.open(path).convert("RGB").quantize(colors=128).save(path, optimize=True)
    print(path)


def run(main):
    """Calls main(), then quits FreeCAD whatever happened (closing its window would ask about documents)."""
    try:
        main()
    finally:
        os._exit(0)
