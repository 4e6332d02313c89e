"""Draws docs/images/connectors.png in FreeCAD: the constant-radius version of a BeCOTS triangle slab on a cone, each
family of congruent connectors in its own colour (built once, placed at every member from the kernel's placements)
and the rods in grey.
Run from the repository, after a build:
  QTWEBENGINE_CHROMIUM_FLAGS=--no-sandbox xvfb-run -a -s "-screen 0 1280x1024x24" freecad docs/diagrams/connectors_figure.py
(prints the figures the docs quote and the picture's path, then quits FreeCAD)."""
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from freecad_figure import ROOT, run, save_view, use_checkout  # noqa: E402

use_checkout("Mod/LatticeWorkbench")

import FreeCAD  # noqa: E402
import Part  # noqa: E402
import numpy as np  # noqa: E402

import steadylattice as sl  # noqa: E402

OUT = os.path.join(ROOT, "docs", "images", "connectors.png")
COLORS = [(0.80, 0.20, 0.20), (0.20, 0.35, 0.85), (0.95, 0.65, 0.10), (0.20, 0.65, 0.30), (0.60, 0.30, 0.70),
          (0.10, 0.65, 0.70)]


def main():
    cone = sl.BecotsMap((0, 0, 0), (0.1, 1, 0.2), (1.3, 1.2, -0.3), (1, 0, 0.1))
    lat = sl.becots_lattice(cone, sl.becots_connectivity("triangle"), (8, 6, 1), 0.01)
    centers, _ = lat.balls()
    a, b, _, _ = lat.beams()
    rho = float(np.min(np.linalg.norm(centers[b] - centers[a], axis=1))) / 9
    low, high = lat.connector_reach_range(rho, sleeve=1.5)
    start = time.time()
    c = lat.connectors(rho, sleeve=1.5, reach=0.5 * (low + high))
    families = c.families
    print("connectors: %d balls, %d beams, rod radius %.4f, reach %.2f (range %.2f to %.2f), %d families (%s), "
          "%d rod lengths, %.1f s" % (lat.ball_count, lat.beam_count, rho, 0.5 * (low + high), low, high,
                                      len(families), ", ".join(str(f["count"]) for f in families), len(c.cut_list),
                                      time.time() - start))
    doc = FreeCAD.newDocument("Connectors")
    objects = []
    for k, f in enumerate(families):
        template = Part.Shape()
        template.importBrepFromString(c.brep(k))
        copies = []
        for P in f["placements"]:
            copy = template.copy()
            copy.transformShape(FreeCAD.Matrix(*P.flatten()))
            copies.append(copy)
        obj = doc.addObject("Part::Feature", f["name"])
        obj.Shape = Part.Compound(copies)
        objects.append((obj, COLORS[k % len(COLORS)]))
    rods = c.rods
    cylinders = [Part.makeCylinder(rho, float(length), FreeCAD.Vector(*s), FreeCAD.Vector(*(e - s)))
                 for s, e, length in zip(rods["starts"], rods["ends"], rods["lengths"])]
    obj = doc.addObject("Part::Feature", "Rods")
    obj.Shape = Part.Compound(cylinders)
    objects.append((obj, (0.72, 0.72, 0.70)))
    doc.recompute()
    if FreeCAD.GuiUp:
        for obj, color in objects:
            obj.ViewObject.ShapeColor = color
        save_view(OUT)
    FreeCAD.closeDocument(doc.Name)


run(main)
