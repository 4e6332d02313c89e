"""A CurvedLattice object's kernel work: its four corners (typed, or read from linked vertices), the whole turns
added to U and V, and the BeCOTS lattice the kernel lays on the field through them (steadylattice.becots_lattice,
docs/cots.md), or on a linked face that the field then follows (face_field), closed into a ring when its groups come
round to the first ones (curved_ring)."""
import math

import FreeCAD

from latticewb.kernel import curved_ring, face_field

CONNECTIVITIES = ["triangle", "kagome", "honeycomb"]
CORNERS = "ABCD"
TURNS = ("TurnsU", "TurnsV")
MAX_TURNS = 100000  # the kernel's limit on a map's branches (kCotsMaxBranch, steady/cots/cots_map.hpp)


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


def turns(obj):
    """(TurnsU, TurnsV); 0 for a document saved before they existed."""
    return tuple(getattr(obj, name, 0) for name in TURNS)


def _turned(obj):
    """The names of the turns properties that are set ('TurnsU', 'TurnsU, TurnsV'), for messages."""
    return ", ".join(name for name, k in zip(TURNS, turns(obj)) if k)


def branches(principal, turns_uv):
    """The kernel's branches (k_u, k_v) for TurnsU, TurnsV on the map with principal angles: each turn goes on the
    way that direction already turns from A (toward D for U, toward B for V), so a positive TurnsU always lengthens
    the U side by whole turns and -1 takes the other way round (a quarter turn becomes three quarters)."""
    w_u, w_v = principal.log_u.imag, principal.log_v.imag
    return turns_uv[0] * curved_ring.turn_sense(w_u, w_v), turns_uv[1] * curved_ring.turn_sense(w_v, w_u)


def becots_map(obj, corners=None):
    """The steadylattice.BecotsMap through the corners (default: corner_points(obj)), with the whole turns TurnsU
    and TurnsV added (the kernel's ValueError names the corners it refuses: 'corners A, D: adjacent corners
    coincide ...', the names of the properties)."""
    import steadylattice as sl
    a, b, c, d = (tuple(p) for p in (corners if corners is not None else corner_points(obj)))
    principal = sl.BecotsMap(a, b, c, d)
    if turns(obj) == (0, 0):
        return principal
    try:
        return sl.BecotsMap(a, b, c, d, branches=branches(principal, turns(obj)))
    except ValueError as error:  # a map that cannot turn (a parallelogram: U and V translations)
        raise ValueError("%s: %s" % (_turned(obj), error)) from None


def turn_degrees(becots_map):
    """How far U and V turn about the field's axis from A (degrees, signed about the kernel's axis)."""
    return math.degrees(becots_map.log_u.imag), math.degrees(becots_map.log_v.imag)


def lattice_and_ring(obj):
    """(the steadylattice.Lattice of a CurvedLattice object, where its corners are, and its ring: None, or
    (direction 0 for U or 1 for V, q the groups kept, n the groups asked for) when the groups come round to the
    first ones after q: the ring is then closed, the repeats left out). The Placement is not applied: the corners
    place it. Raises ValueError naming TurnsU/TurnsV when the sheet winds over itself without closing."""
    import steadylattice as sl
    connectivity = obj.Connectivity
    if obj.JoinLayers and obj.Layers > 1:
        # each node joined to its copy in the next layer (the named connectivities join none)
        nodes, beams = sl.becots_connectivity(connectivity)
        connectivity = (nodes, list(beams) + [(n, 0, 0, 1, n) for n in range(len(nodes))])
    on_face = face_field.linked_face(obj)
    if on_face is None:
        field = becots_map(obj)
        result = sl.becots_lattice(field, connectivity, (obj.CellsU, obj.CellsV, obj.Layers), obj.NodeRadius.Value,
                                   layer_raise=obj.LayerRaise.Value, beam_ratio=obj.BeamRatio,
                                   layer_offset=obj.LayerOffset.Value)
    else:
        field, result = face_field.lay_on_face(obj, *on_face, corner_points(obj), connectivity, turns(obj),
                                               lambda *corners: becots_map(obj, corners))
    ring = None
    for direction in (0, 1):
        q = curved_ring.closing_count(result, field, direction)
        if q is not None:
            asked = result.counts[direction]
            result = curved_ring.closed_ring(result, direction, q, "Cells" + "UV"[direction])
            ring = (direction, q, asked)
            break
    if turns(obj) != (0, 0):
        found, count = curved_ring.far_contacts(result, ring[:2] if ring else None)
        if count:
            degrees = [abs(d) for d in turn_degrees(field)]
            raise ValueError("%s: the sheet winds over itself (U turns %.1f, V %.1f degrees about its axis) and "
                             "%d pairs of elements of distant groups meet: %s%s; change the turns, the cells or the "
                             "corners (a ring closes when a group falls exactly on the first)"
                             % (_turned(obj), degrees[0], degrees[1], count, "; ".join(found),
                                "; ..." if count > len(found) else ""))
    return result, ring


def lattice(obj):
    """The steadylattice.Lattice of a CurvedLattice object (lattice_and_ring without the ring)."""
    return lattice_and_ring(obj)[0]


def default_corners(size=40.0):
    """Corners of a sheet rolled a little about a vertical axis: a starting point to edit."""
    return [FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(0, 0, size), FreeCAD.Vector(size, 0.25 * size, size * 1.05),
            FreeCAD.Vector(size, 0.25 * size, 0)]
