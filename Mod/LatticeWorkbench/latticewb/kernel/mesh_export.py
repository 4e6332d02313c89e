"""Printer files of the workbench's lattices, straight from the kernel's lattice meshes (no B-rep): binary STL
(streamed), OBJ, and 3MF as a beam lattice with its mesh riding along for viewers. A LatticePart goes to STL and
OBJ as the lattice trimmed into its body's mesh (with its skin: the body's inner offset, made by OpenCASCADE), and
to 3MF as a beam lattice clipped by its body's mesh (the printer clips)."""
from latticewb.kernel import curved_lattice, lattice_part, steady_lattice
from latticewb.utils import types

MESH_EXTENSIONS = (".stl", ".obj", ".3mf")
# The representation mesh of a 3MF beam lattice is left out above this many beams (it would dwarf the beams).
REPRESENTATION_BEAM_LIMIT = 200000


def default_tolerance(lattice):
    """A chord tolerance of 2 % of the smallest ball radius: about 16 segments around a beam as thick as its node."""
    radii = lattice.balls()[1]
    return 0.02 * float(radii.min())


def body_mesh(obj, tolerance):
    """(vertices, triangles) of a LatticePart's body tessellated by FreeCAD, in document coordinates."""
    if obj.Body is None:
        raise ValueError("Body: a LatticePart needs a body for a mesh or a clipped beam lattice")
    shape = obj.Body.Shape
    if shape.isNull() or not shape.Solids:
        raise ValueError("Body: %s holds no solid" % obj.Body.Label)
    return _tessellated(shape, tolerance)


def part_meshes(obj, tolerance):
    """(placed lattice, body mesh, inner mesh or None, trim arguments) of a LatticePart: the body tessellated by
    FreeCAD within `tolerance`, with a skin its inner offset too, and the keyword arguments of the kernel's trimmed
    mesh for the part's policy (clip; bridge with the body's B-rep and the skin's thickness)."""
    lattice, body, policy, skin, _ = lattice_part.kernel_request(obj)
    if body is None:
        raise ValueError("Body: a LatticePart without a body has no trimmed mesh; export its SteadyLattice")
    if policy not in ("clip", "bridge"):
        raise ValueError("Policy: a trimmed mesh clips the lattice at the body (clip) or bridges it (bridge); got %r, "
                         "which only the B-rep part has (export it as STEP, or change Policy)" % policy)
    inner = None
    if skin > 0.0:
        offset = obj.Body.Shape.makeOffsetShape(-skin, 1e-6 * max(1.0, obj.Body.Shape.BoundBox.DiagonalLength))
        if offset.isNull() or not offset.Solids:
            raise ValueError("Skin: the body has no inner offset %g mm thick" % skin)
        inner = _tessellated(offset, tolerance)
    trim = {"policy": policy, "brep": body, "skin": skin} if policy == "bridge" else {}
    return lattice, body_mesh(obj, tolerance), inner, trim


def _tessellated(shape, tolerance):
    import numpy as np
    points, facets = shape.tessellate(tolerance)
    return (np.array([(p.x, p.y, p.z) for p in points], dtype=float), np.array(facets, dtype=np.int64))


def write_mesh_file(obj, path, extension, tolerance=None, report=None):
    """Writes `obj` (a SteadyLattice or CurvedLattice, or a LatticePart) to `path`. tolerance: the chord tolerance
    of the mesh in document units (None: default_tolerance). report(fraction) -> False cancels
    (steadylattice.Cancelled, no file written). Returns the kernel's stats."""
    stats = {}
    if types.is_part(obj) and extension in (".stl", ".obj"):
        lattice = lattice_part.kernel_request(obj)[0]
        tolerance = tolerance or default_tolerance(lattice)
        lattice, body, inner, trim = part_meshes(obj, tolerance)
        if extension == ".stl":
            lattice.write_stl(path, tolerance, name=obj.Label, body=body, inner=inner, progress=report, stats=stats,
                              **trim)
        else:
            lattice.write_obj(path, tolerance, name=obj.Label, body=body, inner=inner, progress=report, **trim)
        return stats
    if types.is_part(obj):
        lattice, body, policy, skin, _ = lattice_part.kernel_request(obj)
        if policy != "clip":
            raise ValueError("Policy: a 3MF beam lattice is clipped by the printer at the body (clip); got %r: "
                             "export the part as STL, OBJ or STEP" % policy)
        if skin > 0.0:
            raise ValueError("%s: a skin is not part of a 3MF beam lattice yet; export it as STEP" % obj.Label)
        tolerance = tolerance or default_tolerance(lattice)
        lattice.write_3mf(path, beam_lattice=True, name=obj.Label, clipping=body_mesh(obj, tolerance),
                          progress=report, stats=stats)
        return stats
    if not types.is_part_lattice(obj):
        raise ValueError("%s: only a SteadyLattice, a CurvedLattice or a LatticePart is written as a mesh" % obj.Label)
    lattice = (curved_lattice if types.is_curved_lattice(obj) else steady_lattice).lattice(obj)
    tolerance = tolerance or default_tolerance(lattice)
    if extension == ".stl":
        lattice.write_stl(path, tolerance, name=obj.Label, progress=report, stats=stats)
    elif extension == ".obj":
        lattice.write_obj(path, tolerance, name=obj.Label, progress=report)
    else:
        with_mesh = lattice.beam_count <= REPRESENTATION_BEAM_LIMIT
        lattice.write_3mf(path, tolerance if with_mesh else None, beam_lattice=True, name=obj.Label,
                          progress=report, stats=stats)
    return stats
