"""The shape a SteadyLattice shows: its balls and beams as solids (a compound, not fused), or, past a budget,
a light preview of beam axes. Exact trimmed B-rep parts are the job of LatticePart."""
import FreeCAD
import Part

# Building one OpenCASCADE primitive per element from Python costs ~0.2 ms; past this many elements the
# feature shows beam axes instead, so that a parameter change stays interactive.
MAX_SOLID_ELEMENTS = 5000


def beam_frustum(ca, ra, cb, rb):
    """The lateral part of the convex hull of balls (ca, ra) and (cb, rb): a cone frustum between the two
    tangent circles, or None when one ball contains the other."""
    axis = cb - ca
    length = axis.Length
    if length <= abs(ra - rb):
        return None
    axis.normalize()
    sin_phi = (ra - rb) / length
    cos_phi = (1.0 - sin_phi * sin_phi) ** 0.5
    start = ca + axis * (ra * sin_phi)
    height = length * cos_phi * cos_phi  # from ra sin(phi) to length + rb sin(phi)
    if ra == rb:
        return Part.makeCylinder(ra, height, start, axis)
    return Part.makeCone(ra * cos_phi, rb * cos_phi, height, start, axis)


def lattice_shape(lattice):
    centers, radii = lattice.balls()
    a, b, ra, rb = lattice.beams()
    points = [FreeCAD.Vector(*c) for c in centers.tolist()]
    if len(points) + len(a) > MAX_SOLID_ELEMENTS:
        edges = [Part.LineSegment(points[i], points[j]).toShape() for i, j in zip(a.tolist(), b.tolist())]
        return Part.Compound(edges if edges else [Part.Vertex(p) for p in points])
    solids = [Part.makeSphere(r, p) for p, r in zip(points, radii.tolist())]
    for i, j, r1, r2 in zip(a.tolist(), b.tolist(), ra.tolist(), rb.tolist()):
        frustum = beam_frustum(points[i], r1, points[j], r2)
        if frustum is not None:
            solids.append(frustum)
    return Part.Compound(solids)
