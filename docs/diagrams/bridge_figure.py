"""Draws docs/images/bridge_fill.png in FreeCAD: a conformal BeCOTS stack (polar discs of triangles whose rings follow
the wall, four layers joined, the ring open by two spacings since a whole turn would make corners coincide)
filling a cylinder with the 'bridge' policy; the body half transparent, the bridges (from the kernel's
bridge_plan) overlaid in red, a hair thicker than they are so that they show. The stack is the one of
tests/python/test_bridge.py, denser.
Run from the repository, after a build:
  QTWEBENGINE_CHROMIUM_FLAGS=--no-sandbox xvfb-run -a -s "-screen 0 1280x1024x24" freecad docs/diagrams/bridge_figure.py
(prints the figures the docs quote and the picture's path, then quits FreeCAD)."""
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from freecad_figure import ROOT, run, save_view, use_checkout  # noqa: E402

use_checkout("Mod/LatticeWorkbench")

import FreeCAD  # noqa: E402
import Part  # noqa: E402

import steadylattice as sl  # noqa: E402

OUT = os.path.join(ROOT, "docs", "images", "bridge_fill.png")


def stack():
    nu, nv, layers = 24, 6, 4
    m = sl.BecotsMap.from_field((0, 0, 1.0), (0, 0, 1), (7.0, 0, 1.0), complex(0, 2 * math.pi * nu / (nu + 1)),
                                complex(math.log(24.0 / 7.0), 0))
    nodes, beams = sl.becots_connectivity("triangle")
    beams = list(beams) + [(n, 0, 0, 1, n) for n in range(len(nodes))]
    return sl.becots_lattice(m, (nodes, beams), (nu, nv, layers), 0.35, layer_raise=2.5, beam_ratio=0.5)


def main():
    doc = FreeCAD.newDocument("BridgeFill")
    cylinder = Part.makeCylinder(20.0, 22.0, FreeCAD.Vector(0, 0, -1))
    lat = stack()
    stats = {}
    start = time.time()
    text = lat.brep(cylinder.exportBrepToString(), "bridge", stats=stats)
    seconds = time.time() - start
    props = sl.brep_properties(text)
    print("bridge fill: %d hubs, %d kept whole, %d lost a neighbour, %d bridges (%d blocked, %d ambiguous), valid %s, "
          "%d solid(s), volume %.3f mm^3, %.1f s" % (
              lat.ball_count, stats["kept_hubs"], stats["lost_neighbour_hubs"], stats["bridges"],
              stats["blocked_bridges"], stats["ambiguous_bridges"], props["valid"], props["solids"], props["volume"],
              seconds))
    shape = Part.Shape()
    shape.importBrepFromString(text)
    part = doc.addObject("Part::Feature", "Part")
    part.Shape = shape
    body = doc.addObject("Part::Feature", "Body")
    body.Shape = cylinder
    plan = lat.bridge_plan(cylinder.exportBrepToString())
    centers, _ = lat.balls()
    rods = []
    for br in plan["bridges"]:
        start = FreeCAD.Vector(*centers[br["hub"]])
        axis = FreeCAD.Vector(*br["wall"]) - start
        rods.append(Part.makeCylinder(br["radius"] * 1.08, axis.Length, start, axis))
    bridges = doc.addObject("Part::Feature", "Bridges")
    bridges.Shape = Part.Compound(rods)
    doc.recompute()
    if FreeCAD.GuiUp:
        part.ViewObject.ShapeColor = (0.85, 0.55, 0.20)
        bridges.ViewObject.ShapeColor = (0.85, 0.10, 0.10)
        body.ViewObject.ShapeColor = (0.55, 0.65, 0.80)
        body.ViewObject.Transparency = 85
        save_view(OUT)
    FreeCAD.closeDocument(doc.Name)


run(main)
