"""Builds an octet steady lattice with a taper and a twist and writes it as STEP.

Run: freecad -c examples/lattice_to_step.py      (output: $LATTICE_OUT or ./out/octet_lattice.step)
"""
import math
import os
import sys

import FreeCAD

from latticewb import api


def main():
    out_dir = os.environ.get("LATTICE_OUT", os.path.join(os.getcwd(), "out"))
    os.makedirs(out_dir, exist_ok=True)
    doc = FreeCAD.newDocument("LatticeExample")
    # 4 x 3 x 3 octet cells of 10 mm; each cell along W is 3 % smaller and turned 4 degrees about the W axis
    twist = FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), 4.0)
    lattice = api.make_lattice(doc, preset="octet", cells=(4, 3, 3), cell_size=10.0, node_radius=1.4,
                               beam_radius=0.9, step_w=FreeCAD.Placement(FreeCAD.Vector(0, 0, 1), twist),
                               scale_w=0.97)
    doc.recompute()
    if not lattice.isValid():
        raise RuntimeError("the lattice did not build")
    path = api.export([lattice], os.path.join(out_dir, "octet_lattice.step"))
    json_path = api.export([lattice], os.path.join(out_dir, "octet_lattice.json"))
    FreeCAD.Console.PrintMessage("wrote %s (%d balls, %d beams) and %s\n"
                                 % (path, lattice.BallCount, lattice.BeamCount, json_path))
    doc.saveAs(os.path.join(out_dir, "octet_lattice.FCStd"))
    return path


if __name__ in ("__main__", "lattice_to_step"):
    try:
        main()
    except Exception as error:  # freecad -c exits 0 on an uncaught exception: make failure visible
        FreeCAD.Console.PrintError("lattice_to_step failed: %s\n" % error)
        sys.exit(1)
    if not FreeCAD.GuiUp:
        sys.exit(0)
