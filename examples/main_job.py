"""The main job of the README's first command: a steady lattice trimmed into a part with a skin, exported as STEP.

A twisted, tapered octet lattice fills a cylindrical part with a 1.2 mm wall. The part is one exact B-rep solid
(hubs inside the body kept whole, only those crossing its boundary cut); the STEP file holds the skin and the
lattice as two named, coloured parts. Also writes the part as BREP, as a closed STL mesh for printing (made from
the lattice, not from the B-rep; chord tolerance 0.05 mm) and the FreeCAD document.
Run: freecad -c examples/main_job.py      (output: $LATTICE_OUT or ./out/)
"""
import os
import time

import FreeCAD

from latticewb import api
from latticewb.macro import run_macro


def add_part(doc):
    """The main job's lattice, body and part (not yet recomputed); the benchmarks build the same."""
    # 6 x 6 x 4 octet cells of 8 mm; beams under half their nodes' radius so that every hub is clean
    lattice = api.make_lattice(doc, preset="octet", cells=(6, 6, 4), cell_size=8.0, node_radius=1.3,
                               beam_radius=0.55, twist_w=3.0, taper_w=-1.5)
    body = doc.addObject("Part::Cylinder", "Body")
    body.Radius, body.Height = 20.0, 28.0
    body.Placement.Base = FreeCAD.Vector(24.0, 24.0, 2.0)
    return api.make_part(doc, lattice, body, policy="clip", skin=1.2)


def main():
    out_dir = os.environ.get("LATTICE_OUT", os.path.join(os.getcwd(), "out"))
    os.makedirs(out_dir, exist_ok=True)
    start = time.time()
    doc = FreeCAD.newDocument("MainJob")
    part = add_part(doc)
    lattice, body = part.Lattice, part.Body
    doc.recompute()
    if not part.isValid() or not part.Shape.isValid():
        raise RuntimeError("the part did not build")
    step = api.export([part], os.path.join(out_dir, "lattice_part.step"))
    api.export([part], os.path.join(out_dir, "lattice_part.brep"))
    api.export([part], os.path.join(out_dir, "lattice_part.stl"), tolerance=0.05)
    doc.saveAs(os.path.join(out_dir, "lattice_part.FCStd"))
    FreeCAD.Console.PrintMessage(
        "main job: %d beams trimmed into %s with a 1.2 mm skin: %d solid(s), %d faces, volume %.1f mm^3, valid, "
        "in %.1f s -> %s\n" % (lattice.BeamCount, body.Label, len(part.Shape.Solids), part.FaceCount, part.Volume,
                                time.time() - start, step))
    return step


# freecad -c names the script's module after its file
if __name__ in ("__main__", "main_job"):
    run_macro(main, "main_job")
