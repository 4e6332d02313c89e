"""The shape of a SteadyLattice shown as Solids: its balls and beams as separate solids (a compound, not fused).
Exact trimmed B-rep parts are the job of LatticePart; large lattices are shown by the preview."""
import FreeCAD
import Part

# Building one OpenCASCADE primitive per element from Python costs ~0.2 ms: up to this many elements the
# Auto representation shows solids and a parameter change stays interactive.
MAX_SOLID_ELEMENTS = 5000
# Past this many elements a compound of separate solids takes minutes and gigabytes: refused, with a pointer to
# the preview (display) and LatticePart (exact geometry).
MAX_SEPARATE_SOLIDS = 200000
_SAME_RADIUS = 1e-7  # mm: Precision::Confusion, below which BRepPrimAPI_MakeCone fails
_REPORT_EVERY = 500  # elements between progress reports (~0.1 s of work)


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
    r1, r2 = ra * cos_phi, rb * cos_phi
    if abs(r1 - r2) < _SAME_RADIUS:  # OpenCASCADE refuses a cone whose radii agree to its confusion tolerance
        return Part.makeCylinder(0.5 * (r1 + r2), height, start, axis)
    return Part.makeCone(r1, r2, height, start, axis)


def lattice_shape(lattice, report=None, ball_mask=None, beam_mask=None):
    """The balls and beams as separate solids (only those the masks keep, when given: a filtered lattice).
    report(fraction) -> False cancels (steadylattice.Cancelled)."""
    from latticewb.utils.progress import check_cancelled
    elements = (lattice.ball_count if ball_mask is None else int(ball_mask.sum())) + \
        (lattice.beam_count if beam_mask is None else int(beam_mask.sum()))
    if elements > MAX_SEPARATE_SOLIDS:
        raise ValueError("Representation: %d balls and beams are too many to build as separate solids (at most %d); "
                         "use the Preview representation to see it, or a LatticePart for exact geometry"
                         % (elements, MAX_SEPARATE_SOLIDS))
    centers, radii = lattice.balls()
    a, b, ra, rb = lattice.beams()
    points = [FreeCAD.Vector(*c) for c in centers.tolist()]
    kept_balls = range(len(points)) if ball_mask is None else ball_mask.nonzero()[0].tolist()
    if beam_mask is not None:
        a, b, ra, rb = a[beam_mask], b[beam_mask], ra[beam_mask], rb[beam_mask]
    solids = []
    for q, index in enumerate(kept_balls):
        if q % _REPORT_EVERY == 0:
            check_cancelled(report, q / elements)
        solids.append(Part.makeSphere(float(radii[index]), points[index]))
    for q, (i, j, r1, r2) in enumerate(zip(a.tolist(), b.tolist(), ra.tolist(), rb.tolist())):
        if q % _REPORT_EVERY == 0:
            check_cancelled(report, (len(kept_balls) + q) / elements)
        frustum = beam_frustum(points[i], r1, points[j], r2)
        if frustum is not None:
            solids.append(frustum)
    return Part.Compound(solids)


def empty_shape():
    """The Shape of a lattice shown as a preview: nothing for FreeCAD to tessellate (the view provider draws the
    beam axes itself; exports build the solids on demand)."""
    return Part.Compound([])


def exact_solid(lattice, report=None):
    """The lattice as one exact B-rep solid (the union of its balls and beams), built by the kernel.
    report(fraction) -> False cancels (steadylattice.Cancelled)."""
    shape = Part.Shape()
    shape.importBrepFromString(lattice.brep(progress=report))
    return shape
