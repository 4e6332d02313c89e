# LatticeWorkbench, App side (runs in freecadcmd too). FreeCAD puts this folder on sys.path, which makes the
# package `latticewb` importable; its features need no GUI.
