"""Mass properties and density targeting: a graded Kelvin lattice scaled to 12 % relative density, its exact
volume, area, centroid, mass and inertia (closed form), written to a text report; then 25 g of Ti-6Al-4V.

Run: freecad -c examples/density_target.py      (output: $LATTICE_OUT or ./out/)
"""
import os

import FreeCAD

from latticewb import api
from latticewb.kernel import mass
from latticewb.macro import run_macro


def main():
    out_dir = os.environ.get("LATTICE_OUT", os.path.join(os.getcwd(), "out"))
    os.makedirs(out_dir, exist_ok=True)
    doc = FreeCAD.newDocument("DensityTarget")
    lattice = api.make_lattice(doc, preset="Kelvin", cells=(6, 6, 6), cell_size=8.0, node_radius=0.9,
                               beam_radius=0.45, taper_w=-2.0)
    lattice.Density = 4.43  # g/cm^3, Ti-6Al-4V
    doc.recompute()
    lines = []
    scale = api.target_density(lattice, relative_density=0.12)
    doc.recompute()
    lines.append("12 %% relative density: radii scaled by %.6f" % scale)
    lines.append(mass.report_text(lattice, api.properties(lattice)))
    scale = api.target_density(lattice, mass=0.025)
    doc.recompute()
    lines.append("25 g: radii scaled by %.6f" % scale)
    lines.append(mass.report_text(lattice, api.properties(lattice)))
    path = os.path.join(out_dir, "density_target.txt")
    with open(path, "w") as f:
        f.write("\n\n".join(lines) + "\n")
    FreeCAD.Console.PrintMessage("\n".join(lines) + "\n")
    return path


if __name__ in ("__main__", "density_target"):
    run_macro(main, "density_target")
