"""Draws docs/images/face_lattice.png in FreeCAD: a CurvedLattice laid on the conical face of a cone (FaceLink), a
closed ring of 12 groups around it in 3 layers going into the body, trimmed into the cone by a LatticePart with the
'bridge' policy; the cone half transparent.
Run from the repository, after a build:
  QTWEBENGINE_CHROMIUM_FLAGS=--no-sandbox xvfb-run -a -s "-screen 0 1280x1024x24" freecad docs/diagrams/face_lattice_figure.py
(prints the figures the docs quote and the picture's path, then quits FreeCAD)."""
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from freecad_figure import ROOT, run, save_view, use_checkout  # noqa: E402

use_checkout("Mod/LatticeWorkbench")

import FreeCAD  # noqa: E402

from latticewb import api  # noqa: E402
from latticewb.kernel import curved_lattice  # noqa: E402

OUT = os.path.join(ROOT, "docs", "images", "face_lattice.png")


def main():
    doc = FreeCAD.newDocument("FaceLattice")
    cone = doc.addObject("Part::Cone", "Cone")
    cone.Radius1, cone.Radius2, cone.Height = 22.0, 9.0, 30.0
    doc.recompute()
    groups = 12
    step = 2 * math.pi / groups
    V = FreeCAD.Vector
    # A and D at one height, a group's angle apart; B further up: the face's field turns and dilates about its apex
    corners = [V(22, 0, 3), V(13, 0, 24), V(0, 0, 0), V(22 * math.cos(step), 22 * math.sin(step), 3)]
    lattice = api.make_curved_lattice(doc, corners=corners, face=(cone, "Face1"), cells=(groups + 1, 6),
                                      turns=(1, 0), layers=3, layer_offset=2.2, node_radius=0.8, beam_ratio=0.5)
    doc.recompute()
    lat = curved_lattice.lattice(lattice)
    start = time.time()
    part = api.make_part(doc, lattice, cone, policy="bridge")
    doc.recompute()
    seconds = time.time() - start
    stats = {}
    lat.brep(cone.Shape.exportBrepToString(), "bridge", stats=stats)
    print("face lattice: %s groups, %d balls, %d beams; part valid %s, %d solid(s), volume %.3f mm^3, %.1f s; %d hubs "
          "kept, %d bridges (%d rerouted), %d blocked" % (
              lat.counts, lat.ball_count, lat.beam_count, part.Shape.isValid(), len(part.Shape.Solids),
              part.Shape.Volume, seconds, stats["kept_hubs"], stats["bridges"], stats["rerouted_bridges"],
              stats["blocked_bridges"]))
    if FreeCAD.GuiUp:
        lattice.ViewObject.Visibility = False
        part.ViewObject.ShapeColor = (0.85, 0.55, 0.20)
        cone.ViewObject.Visibility = True
        cone.ViewObject.ShapeColor = (0.55, 0.65, 0.80)
        cone.ViewObject.Transparency = 80
        save_view(OUT)
    FreeCAD.closeDocument(doc.Name)


run(main)
