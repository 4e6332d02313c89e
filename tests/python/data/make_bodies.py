"""Writes the BREP bodies the module tests trim lattices into (run once with FreeCAD's Python; the files are
committed so the tests need no FreeCAD):  /usr/bin/python3 tests/python/data/make_bodies.py"""
import os
import sys

sys.path.append("/usr/lib/freecad/lib")
import FreeCAD  # noqa: E402
import Part  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
bodies = {
    # Cuts the beams of a unit cubic lattice 0.4 past the nodes at 0 and 0.6 past the nodes at 2.
    "box.brep": Part.makeBox(3.0, 3.0, 3.0, FreeCAD.Vector(-0.4, -0.4, -0.4)),
    # The inner offset of this box by 0.3 is [-0.4, 4.4]^3, which cuts beams between their exit circles.
    "skin_box.brep": Part.makeBox(5.4, 5.4, 5.4, FreeCAD.Vector(-0.7, -0.7, -0.7)),
    "cylinder.brep": Part.makeCylinder(1.6, 4.0, FreeCAD.Vector(1.5, 1.5, -0.5), FreeCAD.Vector(0.1, 0.05, 1.0)),
    "face.brep": Part.makePlane(2.0, 2.0),
    # Conformal fills with bridges (test_bridge.py): a cylinder and a cone frustum about the z axis.
    "bridge_cylinder.brep": Part.makeCylinder(20.0, 22.0, FreeCAD.Vector(0, 0, -1)),
    "bridge_cone.brep": Part.makeCone(22.0, 8.0, 28.0),
    # Dense 3 x 3 x 3 lattices of unit cells (centres 0 to 2.5) trimmed with beams too short for a cut
    # (test_crowded_hubs.py): a box across the middle.
    "dense_box.brep": Part.makeBox(1.75, 1.75, 1.75, FreeCAD.Vector(0.325, 0.325, 0.325)),
    # The same lattices in a cylinder along z through their middle, whose wall crosses thin bands of cone between
    # crowded hubs' collars (crowded_sweep.py --trim-cylinder; docs/brep.md, section 3).
    "dense_cylinder.brep": Part.makeCylinder(1.05, 4.5, FreeCAD.Vector(1.25, 1.25, -1.0)),
}
for name, shape in bodies.items():
    with open(os.path.join(here, name), "w") as f:
        f.write(shape.exportBrepToString())
    print(name, shape.ShapeType, round(shape.Volume, 6) if shape.ShapeType == "Solid" else "")
