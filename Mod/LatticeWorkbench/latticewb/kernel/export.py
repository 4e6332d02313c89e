"""Writing the workbench's objects to files: STEP (named parts; a LatticePart as an assembly of its skin and its
lattice), BREP, and the lattice file (JSON)."""
import os

import FreeCAD

from latticewb.kernel import lattice_part, lattice_shape, steady_lattice
from latticewb.utils import types
from latticewb.utils.progress import LongOperation


def export_shape(obj):
    """The shape an export writes for `obj`: its Shape, or for a lattice shown as a preview (empty Shape) its
    balls and beams as solids, built now."""
    if types.is_lattice(obj) and not obj.Shape.Solids:
        shape = lattice_shape.lattice_shape(steady_lattice.build_lattice(obj))
        shape.Placement = obj.Placement
        return shape
    return obj.Shape


def _export_step(objects, path):
    """STEP with one named part per object (FreeCAD's Import keeps labels and colours); a single LatticePart is
    written as an assembly of its skin and its lattice, two named and coloured parts."""
    import Import
    if len(objects) == 1 and types.is_part(objects[0]):
        with LongOperation("Exporting %s" % objects[0].Label) as report:
            lattice_part.write_step_assembly(objects[0], path, report)  # trims again: shows progress, cancellable
        return
    shapes = [export_shape(o) for o in objects]
    if all(shape is o.Shape for shape, o in zip(shapes, objects)):
        Import.export(objects, path)
        return
    # some shapes were built on demand: export named copies from a scratch document
    try:
        scratch = FreeCAD.newDocument("LatticeExport", "LatticeExport", True)  # hidden, where supported
    except TypeError:
        scratch = FreeCAD.newDocument("LatticeExport")
    try:
        copies = []
        for o, shape in zip(objects, shapes):
            copy = scratch.addObject("Part::Feature", o.Name)
            copy.Label = o.Label
            copy.Shape = shape
            copies.append(copy)
        Import.export(copies, path)
    finally:
        FreeCAD.closeDocument(scratch.Name)


def export(objects, path):
    """Writes `objects` to `path`; the format follows the extension:
    .step/.stp (STEP, one part per object with its name; a LatticePart alone: its skin and lattice as two parts),
    .brep/.brp (BREP of the compound),
    .json (the lattice file of a single SteadyLattice).
    Writing a LatticePart's STEP assembly trims it again, with FreeCAD's progress bar; a cancel raises
    steadylattice.Cancelled and writes nothing."""
    objects = list(objects)
    if not objects:
        raise ValueError("objects: nothing to export")
    extension = os.path.splitext(path)[1].lower()
    if extension in (".step", ".stp"):
        _export_step(objects, path)
    elif extension in (".brep", ".brp"):
        import Part
        Part.Compound([export_shape(o) for o in objects]).exportBrep(path)
    elif extension == ".json":
        if len(objects) != 1 or not types.is_lattice(objects[0]):
            raise ValueError("objects: a .json lattice file holds exactly one SteadyLattice")
        with open(path, "w") as f:
            f.write(steady_lattice.lattice(objects[0]).to_json())
    else:
        raise ValueError("path: unknown format %r (use .step, .stp, .brep, .brp or .json)" % extension)
    if not os.path.isfile(path):
        raise RuntimeError("export: %s was not written" % path)
    return path
