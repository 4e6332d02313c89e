"""A graded steady lattice exported as it is: STEP (balls and beams), the lattice file (JSON), the FreeCAD document.

Builds an octet lattice with a taper and a twist along W.
Run: freecad -c examples/graded_lattice.py      (output: $LATTICE_OUT or ./out/)
"""
import os

import FreeCAD

from latticewb import api
from latticewb.macro import run_macro


def main():
    out_dir = os.environ.get("LATTICE_OUT", os.path.join(os.getcwd(), "out"))
    os.makedirs(out_dir, exist_ok=True)
    doc = FreeCAD.newDocument("LatticeExample")
    # 4 x 3 x 3 octet cells of 10 mm; each layer along W is 3 % smaller and turned 4 degrees about the centre line
    lattice = api.make_lattice(doc, preset="octet", cells=(4, 3, 3), cell_size=10.0, node_radius=1.4,
                               beam_radius=0.9, taper_w=-3.0, twist_w=4.0)
    doc.recompute()
    if not lattice.isValid():
        raise RuntimeError("the lattice did not build")
    path = api.export([lattice], os.path.join(out_dir, "octet_lattice.step"))
    json_path = api.export([lattice], os.path.join(out_dir, "octet_lattice.json"))
    FreeCAD.Console.PrintMessage("wrote %s (%d balls, %d beams) and %s\n"
                                 % (path, lattice.BallCount, lattice.BeamCount, json_path))
    doc.saveAs(os.path.join(out_dir, "octet_lattice.FCStd"))
    return path


# freecad -c names the script's module after its file
if __name__ in ("__main__", "graded_lattice"):
    run_macro(main, "graded_lattice")
