"""LatticeWorkbench: steady lattices in FreeCAD.

features/  App-side document objects (usable from freecadcmd)
gui/       commands and view providers (need the GUI)
api.py     what a Python-console user or a macro calls
"""
