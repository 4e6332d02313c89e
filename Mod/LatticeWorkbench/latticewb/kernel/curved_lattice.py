"""A CurvedLattice object's kernel work: its four corners (typed, or read from linked vertices) and the BeCOTS
lattice the kernel lays on the field through them (steadylattice.becots_lattice, docs/cots.md)."""
import FreeCAD

CONNECTIVITIES = ["triangle", "kagome", "honeycomb"]
CORNERS = "ABCD"


def linked_point(obj, corner):
    """The global position of the vertex linked as `corner` ('A'..'D'), or None when no vertex is linked.

    The link is (object, [sub-element]): a sketch's vertex ('Vertex3'), a Part vertex, a Draft point (its only
    vertex; no sub-element needed). The point is placed by the object's own placement (a container's, such as a
    PartDesign Body's, is not applied).
    Raises ValueError naming the link property when the link does not give one vertex."""
    link = getattr(obj, corner + "Link")
    if link is None:
        return None
    target, subs = link
    prop = corner + "Link"
    if getattr(target, "TypeId", "") == "Sketcher::SketchObject":
        return _sketch_point(target, [s for s in subs if s], prop)
    shape = getattr(target, "Shape", None)
    if shape is None or shape.isNull():
        raise ValueError("%s: %s has no shape to take a vertex from" % (prop, target.Label))
    subs = [s for s in subs if s]
    if not subs:
        if len(shape.Vertexes) != 1:
            raise ValueError("%s: %s has %d vertices; pick one (as %s.VertexN)"
                             % (prop, target.Label, len(shape.Vertexes), target.Name))
        return shape.Vertexes[0].Point
    if len(subs) != 1 or not subs[0].startswith("Vertex"):
        raise ValueError("%s: link one vertex of %s (got %s)" % (prop, target.Label, ", ".join(subs)))
    try:
        vertex = shape.getElement(subs[0])
    except Exception:
        raise ValueError("%s: %s has no %s" % (prop, target.Label, subs[0])) from None
    return vertex.Point


def _sketch_point(sketch, subs, prop):
    """A sketch's vertex ('VertexN', as the 3D view names it): a sketch's Shape holds its edges but not its lone
    points, so the point comes from the sketch's geometry, placed by the sketch's Placement."""
    if len(subs) != 1 or not subs[0].startswith("Vertex") or not subs[0][6:].isdigit():
        raise ValueError("%s: link one vertex of %s (as %s.VertexN; got %s)"
                         % (prop, sketch.Label, sketch.Name, ", ".join(subs) or "none"))
    try:
        geo, pos = sketch.getGeoVertexIndex(int(subs[0][6:]) - 1)
        if geo < -2:  # no such vertex: FreeCAD answers (-2000, 0)
            raise ValueError
        local = sketch.getPoint(geo, pos)
    except (ValueError, IndexError):
        raise ValueError("%s: %s has no %s" % (prop, sketch.Label, subs[0])) from None
    return sketch.Placement.multVec(local)


def corner_points(obj):
    """The corners A, B, C, D as FreeCAD vectors: the linked vertex where a corner has one, else the property."""
    points = []
    for corner in CORNERS:
        p = linked_point(obj, corner)
        points.append(p if p is not None else getattr(obj, corner))
    return points


def becots_map(obj):
    """The steadylattice.BecotsMap through the corners (the kernel's ValueError names the corners it refuses:
    'corners A, D: adjacent corners coincide ...', the names of the properties)."""
    import steadylattice as sl
    a, b, c, d = (tuple(p) for p in corner_points(obj))
    return sl.BecotsMap(a, b, c, d)


def lattice(obj):
    """The steadylattice.Lattice of a CurvedLattice object, where its corners are (its Placement is not applied:
    the corners place it)."""
    import steadylattice as sl
    connectivity = obj.Connectivity
    if obj.JoinLayers and obj.Layers > 1:
        # each node joined to its copy in the next layer (the named connectivities join none)
        nodes, beams = sl.becots_connectivity(connectivity)
        connectivity = (nodes, list(beams) + [(n, 0, 0, 1, n) for n in range(len(nodes))])
    return sl.becots_lattice(becots_map(obj), connectivity, (obj.CellsU, obj.CellsV, obj.Layers),
                             obj.NodeRadius.Value, layer_raise=obj.LayerRaise.Value, beam_ratio=obj.BeamRatio)


def default_corners(size=40.0):
    """Corners of a sheet rolled a little about a vertical axis: a starting point to edit."""
    return [FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(0, 0, size), FreeCAD.Vector(size, 0.25 * size, size * 1.05),
            FreeCAD.Vector(size, 0.25 * size, 0)]
