"""Mass properties of the workbench's objects, and density targeting.

A SteadyLattice's properties come from the kernel in closed form (row and slab sums over similar hubs: exact and
near-constant time, whatever the number of beams); a LatticePart's from OpenCASCADE's integration over its B-rep
(it is trimmed, so no longer steady). Mass uses the object's Density (g/cm^3)."""
import math

import FreeCAD

from latticewb.kernel import steady_lattice
from latticewb.utils import types

# g/cm^3 -> kg/mm^3 (FreeCAD lengths are mm): 1 g/cm^3 = 1e-6 kg/mm^3
_KG_PER_MM3 = 1e-6


def properties(obj):
    """{volume (mm^3), area (mm^2), centroid (mm), inertia (3x3 kg mm^2 about the centroid), mass (kg), density
    (g/cm^3), method, overlaps (pairs of hubs that overlap: their exact union was used)} of a SteadyLattice (closed form) or any object with a solid Shape (B-rep integration)."""
    density = getattr(obj, "Density", 1.0)
    if not (math.isfinite(density) and density > 0.0):
        raise ValueError("Density: must be > 0 (got %g)" % density)
    lattice = types.is_lattice(obj)
    if lattice:
        p = steady_lattice.lattice(obj).properties()
        volume, area = p["volume"], p["area"]
        centroid = tuple(float(x) for x in p["centroid"])
        inertia = [[float(x) for x in row] for row in p["inertia"]]  # density 1: mm^5
        method = "closed form (kernel sums over similar hubs)"
        overlaps = p["overlap_count"]
        if overlaps:
            # Not clean: say so, and which hubs; the kernel replaced their sum by their exact union.
            if p["moved_cuts"]:
                method += ", with %d beam cuts moved past crowded hubs so that hubs do not overlap" % p["moved_cuts"]
            else:
                method += ", plus the exact union of %d overlapping hubs in %d cluster(s)" % (
                    p["union_hubs"], p["union_clusters"])
            FreeCAD.Console.PrintWarning("%s is not clean: %s\n" % (obj.Label, p["overlap_description"]))
    else:
        shape = obj.Shape
        if shape.isNull() or not shape.Solids:
            raise ValueError("%s has no solid to measure" % obj.Label)
        volume, area = shape.Volume, shape.Area
        # a shape read from BREP text is a generic Shape: its solids carry the mass properties
        single = shape.Solids[0] if len(shape.Solids) == 1 else None
        centroid = tuple(single.CenterOfMass) if single else _compound_centroid(shape)
        matrix = single.MatrixOfInertia if single else _compound_inertia(shape, centroid)
        inertia = [[matrix.A[4 * r + c] for c in range(3)] for r in range(3)]
        method = "B-rep integration (OpenCASCADE)"
    rho = density * _KG_PER_MM3
    return {
        "volume": volume, "area": area, "centroid": centroid,
        "inertia": [[rho * x for x in row] for row in inertia],
        "mass": rho * volume, "density": density, "method": method,
        "overlaps": overlaps if lattice else 0,
    }


def _compound_centroid(shape):
    total = sum(s.Volume for s in shape.Solids)
    return tuple(sum(s.Volume * s.CenterOfMass[c] for s in shape.Solids) / total for c in range(3))


def _compound_inertia(shape, centroid):
    """The inertia of disjoint solids about the common centroid (parallel-axis theorem per solid)."""
    total = FreeCAD.Matrix()
    total.A = [0.0] * 16
    values = [0.0] * 9
    for s in shape.Solids:
        m, g, v = s.MatrixOfInertia, s.CenterOfMass, s.Volume
        d = [g[c] - centroid[c] for c in range(3)]
        dd = sum(x * x for x in d)
        for r in range(3):
            for c in range(3):
                values[3 * r + c] += m.A[4 * r + c] + v * ((dd if r == c else 0.0) - d[r] * d[c])
    total.A = [values[0], values[1], values[2], 0, values[3], values[4], values[5], 0, values[6], values[7], values[8], 0,
               0, 0, 0, 1]
    return total


def report_text(obj, p):
    c = p["centroid"]
    rows = ["%s: %s" % (obj.Label, p["method"]),
            "  volume    %.6g mm^3" % p["volume"],
            "  area      %.6g mm^2" % p["area"],
            "  centroid  (%.6g, %.6g, %.6g) mm" % c,
            "  mass      %.6g kg at %.4g g/cm^3" % (p["mass"], p["density"]),
            "  inertia about the centroid (kg mm^2):"]
    rows += ["    [% .6g % .6g % .6g]" % tuple(row) for row in p["inertia"]]
    return "\n".join(rows)


def cells_envelope_volume(obj):
    """Volume of the box of cells of a preset SteadyLattice, each cell scaled with its group (mm^3): the envelope a
    relative density refers to."""
    if obj.Preset == steady_lattice.CUSTOM:
        return None
    lattice = steady_lattice.build_lattice(obj)
    aspect = steady_lattice.cell_aspect(obj)
    cell_volume = obj.CellSize.Value ** 3 * aspect[0] * aspect[1] * aspect[2]
    total = cell_volume
    for step, count in zip((lattice.U, lattice.V, lattice.W), (obj.CellsU, obj.CellsV, obj.CellsW)):
        s3 = step.scale ** 3
        total *= count if abs(s3 - 1.0) < 1e-15 else (s3 ** count - 1.0) / (s3 - 1.0)
    return total


def scale_for_target(obj, relative_density=None, mass=None):
    """The factor on every radius that gives the lattice the target relative density (against its box of cells) or
    the target mass (kg, at its Density)."""
    if (relative_density is None) == (mass is None):
        raise ValueError("give either relative_density or mass")
    if relative_density is not None:
        if not 0.0 < relative_density < 1.0:
            raise ValueError("relative_density: must be in (0, 1) (got %g)" % relative_density)
        envelope = cells_envelope_volume(obj)
        if envelope is None:
            raise ValueError("relative_density: a custom cell has no box of cells; give a mass instead")
        target = relative_density * envelope
    else:
        if not mass > 0.0:
            raise ValueError("mass: must be > 0 (got %g)" % mass)
        target = mass / (getattr(obj, "Density", 1.0) * _KG_PER_MM3)
    return steady_lattice.lattice(obj).radius_scale_for_volume(target)["scale"]


def apply_radius_scale(obj, scale):
    """Multiplies every radius of a SteadyLattice by `scale` (node and beam radii, custom radii and beam ends)."""
    if obj.Preset == steady_lattice.CUSTOM:
        obj.NodeRadii = [r * scale for r in obj.NodeRadii]
        beams = []
        for index, text in enumerate(obj.Beams):
            fields = steady_lattice.parse_beam(text, index)
            head = " ".join(str(x) for x in fields[:5])
            beams.append(head if len(fields) == 5 else "%s %r %r" % (head, fields[5] * scale, fields[6] * scale))
        obj.Beams = beams
    else:
        beam = obj.BeamRadius.Value
        obj.NodeRadius = obj.NodeRadius.Value * scale
        obj.BeamRadius = beam * scale
