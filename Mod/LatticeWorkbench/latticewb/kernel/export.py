"""Writing the workbench's objects to files: STEP (named parts; a LatticePart as an assembly of its skin and its
lattice), BREP, the lattice file (JSON), and printer files (STL, OBJ, 3MF beam lattice: mesh_export)."""
import os

import FreeCAD

from latticewb.kernel import lattice_part, lattice_shape, mesh_export, steady_lattice
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


def _export_step(objects, path, united):
    """STEP with one named part per object (FreeCAD's Import keeps labels and colours); a single LatticePart is
    written as an assembly of its skin and its lattice, two named and coloured parts, or with `united` as one
    solid (the lattice united with its skin)."""
    import Import
    if len(objects) == 1 and types.is_part(objects[0]):
        with LongOperation("Exporting %s" % objects[0].Label) as report:
            # trims again: shows progress, cancellable
            lattice_part.write_step_assembly(objects[0], path, report, united=united)
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


def export(objects, path, tolerance=None, united=False):
    """Writes `objects` to `path`; the format follows the extension:
    .step/.stp (STEP, one part per object with its name; a LatticePart alone: its skin and lattice as two parts,
    or with united=True one solid, the lattice united with its skin: what a mesher for analysis takes,
    docs/fea.md),
    .brep/.brp (BREP of the compound),
    .json (the lattice file of a single SteadyLattice),
    .stl/.obj (a single SteadyLattice's mesh, straight from the kernel, at `tolerance`: the chord error in document
    units, None for 2 % of the smallest ball radius), .3mf (a 3MF beam lattice of a SteadyLattice with its mesh for
    viewers, or of a LatticePart clipped by its body's mesh).
    Writing a LatticePart's STEP assembly trims it again, and meshes take time on large lattices: both show
    FreeCAD's progress bar; a cancel raises steadylattice.Cancelled and writes nothing."""
    objects = list(objects)
    if not objects:
        raise ValueError("objects: nothing to export")
    extension = os.path.splitext(path)[1].lower()
    if extension in (".step", ".stp"):
        _export_step(objects, path, united)
    elif extension in (".brep", ".brp"):
        import Part
        Part.Compound([export_shape(o) for o in objects]).exportBrep(path)
    elif extension == ".json":
        if len(objects) != 1 or not types.is_lattice(objects[0]):
            raise ValueError("objects: a .json lattice file holds exactly one SteadyLattice")
        with open(path, "w") as f:
            f.write(steady_lattice.lattice(objects[0]).to_json())
    elif extension in mesh_export.MESH_EXTENSIONS:
        if len(objects) != 1:
            raise ValueError("objects: a %s file holds exactly one lattice" % extension)
        with LongOperation("Exporting %s" % objects[0].Label) as report:
            mesh_export.write_mesh_file(objects[0], path, extension, tolerance, report)
    else:
        raise ValueError("path: unknown format %r (use .step, .stp, .brep, .brp, .json, .stl, .obj or .3mf)"
                         % extension)
    if not os.path.isfile(path):
        raise RuntimeError("export: %s was not written" % path)
    return path
