"""Draws docs/images/united_mesh.png in FreeCAD: a BCC lattice whose beams are 0.9 of its nodes, so thick that every
beam is too short for its two crowded hubs' collars; the mesh unites those hubs in groups (kernel/src/mesh/
mesh_groups.cpp). The design is one of test_mesh.py's (crowded_sweep.py's BCC at node 0.45, 3 x 3 x 3 cells).
Run from the repository, after a build:
  QTWEBENGINE_CHROMIUM_FLAGS=--no-sandbox xvfb-run -a -s "-screen 0 1280x1024x24" freecad docs/diagrams/united_mesh_figure.py
(prints the figures the docs quote and the picture's path, then quits FreeCAD)."""
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from freecad_figure import ROOT, run, save_view, use_checkout  # noqa: E402

use_checkout("tests/python")

import FreeCAD  # noqa: E402
import Mesh  # noqa: E402

import steadylattice as sl  # noqa: E402
from crowded_sweep import lattice  # noqa: E402

OUT = os.path.join(ROOT, "docs", "images", "united_mesh.png")


def main():
    lat = lattice("BCC", 0.45, 0.9, "screw", (3, 3, 3))
    tolerance = 0.02 * 0.45 * sl.preset("BCC")["neighbour_distance"]
    stats = {}
    start = time.time()
    vertices, triangles = lat.to_mesh(tolerance, stats=stats)
    seconds = time.time() - start
    mesh = Mesh.Mesh([[list(vertices[i]) for i in t] for t in triangles])
    print("united BCC: %d triangles, %d hubs in %d groups (%d short beams), %.1f s; FreeCAD: solid %s, "
          "non-manifold %s, components %d" % (
              len(triangles), stats["foreign_hubs"], stats["foreign_groups"], stats["short_beams"], seconds,
              mesh.isSolid(), mesh.hasNonManifolds(), mesh.countComponents()))
    doc = FreeCAD.newDocument("UnitedMesh")
    feature = doc.addObject("Mesh::Feature", "Lattice")
    feature.Mesh = mesh
    doc.recompute()
    if FreeCAD.GuiUp:
        feature.ViewObject.ShapeColor = (0.85, 0.55, 0.20)
        save_view(OUT)
    FreeCAD.closeDocument(doc.Name)


run(main)
