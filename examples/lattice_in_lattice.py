"""Filters: a fine cubic lattice kept where it meets a coarse octet lattice (Lattice-in-Lattice), then thinned to
the nodes inside a sphere; exported as STEP (its balls and beams).

Run: freecad -c examples/lattice_in_lattice.py      (output: $LATTICE_OUT or ./out/)
"""
import os

import FreeCAD

from latticewb import api
from latticewb.macro import run_macro


def main():
    out_dir = os.environ.get("LATTICE_OUT", os.path.join(os.getcwd(), "out"))
    os.makedirs(out_dir, exist_ok=True)
    doc = FreeCAD.newDocument("LatticeInLattice")
    fine = api.make_lattice(doc, preset="cubic", cells=(16, 16, 16), cell_size=1.5, node_radius=0.25,
                            beam_radius=0.12)
    coarse = api.make_lattice(doc, preset="octet", cells=(2, 2, 2), cell_size=12.0, node_radius=1.8, beam_radius=1.4)
    ball = doc.addObject("Part::Sphere", "Sphere")
    ball.Radius = 11.0
    ball.Placement.Base = FreeCAD.Vector(12, 12, 12)
    lil = api.make_filter(doc, fine, "lattice-in-lattice", coarse=coarse)
    inside = api.make_filter(doc, lil, "inside body", body=ball)  # a cascade: both filters apply
    doc.recompute()
    FreeCAD.Console.PrintMessage("lattice in lattice: %d of %d beams kept, %d inside the sphere\n"
                                 % (lil.BeamCount, fine.BeamCount, inside.BeamCount))
    path = api.export([inside], os.path.join(out_dir, "lattice_in_lattice.step"))
    doc.saveAs(os.path.join(out_dir, "lattice_in_lattice.FCStd"))
    return path


if __name__ in ("__main__", "lattice_in_lattice"):
    run_macro(main, "lattice_in_lattice")
