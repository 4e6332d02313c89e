"""LatticeWorkbench: steady lattices in FreeCAD, in layers like FreeCAD's Draft workbench (each imports only the
layers below it; tests/freecad/test_layers.py checks it):

  utils          type tags, proxies' persistence, progress and cancel, resources
  kernel         document objects -> steadylattice lattices, parts, properties and files
  objects        App-side proxies (SteadyLattice, LatticeFilter, LatticePart): usable from freecadcmd
  taskpanels     GUI task panels
  viewproviders  GUI view providers and the scalable preview
  make           make_* functions: an object, plus its view provider when the GUI is up
  api            what a Python-console user or a macro calls (re-exports)
  gui            commands (toolbar and menu)
  features       kept only so that documents saved before the layers load
"""
