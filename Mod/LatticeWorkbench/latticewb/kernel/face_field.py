"""A CurvedLattice laid on a face of a body (issue 15, item 7: the lattice follows the part).

FaceLink names a planar, cylindrical or conical face. The corners A, B, D (and C on a plane) are projected onto the
face's surface, and the field is made to follow that surface rather than whatever cone would pass through the four
corners: its fixed point and axis are the face's own.

* plane: the planar COTS map through the four projected corners (C included);
* cone: the BeCOTS field about the cone's apex and axis taking A to D along U and A to B along V, each the spiral
  whose log-distance from the apex and turn about the axis are those of the projected corners
  (steadylattice.BecotsMap.from_field); C is where that field puts M(1, 1);
* cylinder: the field has no apex (the screws of a cylinder never dilate), so the lattice is laid directly as a
  steady brick of two coaxial screws taking A to D and A to B; C is again implied.

Layers go inward: LayerOffset moves each layer's corner A along the face's inward normal at A (the sheet's normal,
pointed into the body), as a BeCOTS stack by normal offset (docs/cots.md). TurnsU and TurnsV add whole turns as on a
free CurvedLattice. Every result is an ordinary steadylattice.Lattice: the cone's and the plane's are BeCOTS lattices
(queries on the becots path), the cylinder's a steady brick of screws."""
import math

import FreeCAD

from latticewb.kernel import curved_ring

KINDS = {"Plane": "plane", "Cylinder": "cylinder", "Cone": "cone"}


class ScrewField:
    """What the ring and the messages need of a field without apex: log_u and log_v as ln(scale) + i angle over a
    whole side (the scale is 1 on a cylinder)."""

    def __init__(self, angle_u, angle_v):
        self.log_u, self.log_v = complex(0.0, angle_u), complex(0.0, angle_v)


def linked_face(obj):
    """The linked face (a Part.Face in global coordinates) and its label for messages, or None when FaceLink is
    empty. Raises ValueError naming FaceLink when the link does not give one face."""
    link = getattr(obj, "FaceLink", None)
    if link is None:
        return None
    target, subs = link
    subs = [s for s in subs if s]
    shape = getattr(target, "Shape", None)
    if shape is None or shape.isNull():
        raise ValueError("FaceLink: %s has no shape to take a face from" % target.Label)
    if len(subs) != 1 or not subs[0].startswith("Face"):
        raise ValueError("FaceLink: link one face of %s (as %s.FaceN; got %s)"
                         % (target.Label, target.Name, ", ".join(subs) or "none"))
    try:
        face = shape.getElement(subs[0])
    except Exception:
        raise ValueError("FaceLink: %s has no %s" % (target.Label, subs[0])) from None
    return face, "%s.%s" % (target.Label, subs[0])


def corners_on(face):
    """Corners A, B, C, D spread over a face (from 10 to 40 percent of its first parameter's range and 10 to 90 of
    its second's): where a lattice laid on it starts before the designer moves them."""
    u0, u1, v0, v1 = face.ParameterRange
    at = [(0.1, 0.1), (0.1, 0.9), (0.4, 0.9), (0.4, 0.1)]
    return [face.valueAt(u0 + s * (u1 - u0), v0 + t * (v1 - v0)) for s, t in at]


def surface_kind(face, label):
    """'plane', 'cylinder' or 'cone'; ValueError naming FaceLink for any other surface."""
    name = type(face.Surface).__name__
    if name not in KINDS:
        raise ValueError("FaceLink: %s is a %s surface; a lattice follows planar, cylindrical and conical faces"
                         % (label, name))
    return KINDS[name]


def _unit(v):
    return v / v.Length


def project(face, kind, p, corner):
    """The point of the face's whole surface nearest p (corner: its name, for messages)."""
    s = face.Surface
    if kind == "plane":
        n = _unit(s.Axis)
        return p - n * (p - s.Position).dot(n)
    axis = _unit(s.Axis)
    if kind == "cylinder":
        foot = s.Center + axis * (p - s.Center).dot(axis)
        radial = p - foot
        if radial.Length == 0.0:
            raise ValueError("FaceLink: corner %s lies on the cylinder's axis; it has no nearest point" % corner)
        return foot + _unit(radial) * s.Radius
    apex, rel = s.Apex, p - s.Apex
    radial = rel - axis * rel.dot(axis)
    if radial.Length == 0.0:
        raise ValueError("FaceLink: corner %s lies on the cone's axis; it has no nearest point" % corner)
    # the generator in the corner's meridian plane, on the face's nappe (away from the apex along the axis)
    toward = axis if (s.Center - apex).dot(axis) > 0.0 else -axis
    generator = toward * math.cos(s.SemiAngle) + _unit(radial) * math.sin(abs(s.SemiAngle))
    along = rel.dot(generator)
    if along <= 0.0:
        raise ValueError("FaceLink: corner %s lies beyond the cone's apex" % corner)
    return apex + generator * along


def inward_normal(face, p):
    """The unit normal of the face at p (a point of its surface), pointing into the body (the face's own normal
    follows its orientation in the solid: outward)."""
    u, v = face.Surface.parameter(p)
    n = face.normalAt(u, v)
    return -_unit(n)


def _about(axis, a, b):
    """The signed angle about `axis` from the radial direction of a to that of b (both measured off the axis)."""
    ra, rb = a - axis * a.dot(axis), b - axis * b.dot(axis)
    return math.atan2(axis.dot(ra.cross(rb)), ra.dot(rb))


def _with_turns(angle, other, turns):
    """The principal angle lengthened by whole turns, each the way the side already turns (or the other side does,
    when it does not turn): as TurnsU and TurnsV on a free CurvedLattice."""
    return angle + 2.0 * math.pi * turns * curved_ring.turn_sense(angle, other)


def lay_on_face(obj, face, label, corners, connectivity, turns, planar_map):
    """(field, lattice): the lattice of `obj` (its cells, layers, radii) laid on the face through the projected
    corners. field is a steadylattice.BecotsMap (plane, cone) or a ScrewField (cylinder). planar_map(a, b, c, d)
    makes a free CurvedLattice's map through four corners (its turns added): used on a plane."""
    import steadylattice as sl
    kind = surface_kind(face, label)
    # C is implied by the field on a cylinder or cone (the field has no freedom left once A, B and D are on it)
    a, b, d = (project(face, kind, FreeCAD.Vector(*corners[n]), "ABCD"[n]) for n in (0, 1, 3))
    inward = inward_normal(face, a)
    counts = (obj.CellsU, obj.CellsV, obj.Layers)
    if kind == "cylinder":
        return _screw_lattice(obj, face.Surface, (a, b, d), inward, connectivity, counts, turns)
    if kind == "plane":
        field = planar_map(a, b, project(face, kind, FreeCAD.Vector(*corners[2]), "C"), d)
    else:
        s = face.Surface
        axis = _unit(s.Axis)
        angle_u, angle_v = _about(axis, a - s.Apex, d - s.Apex), _about(axis, a - s.Apex, b - s.Apex)
        angle_u, angle_v = _with_turns(angle_u, angle_v, turns[0]), _with_turns(angle_v, angle_u, turns[1])
        distance = (a - s.Apex).Length
        log_u = complex(math.log((d - s.Apex).Length / distance), angle_u)
        log_v = complex(math.log((b - s.Apex).Length / distance), angle_v)
        field = sl.BecotsMap.from_field(tuple(s.Apex), tuple(axis), tuple(a), log_u, log_v)
    # LayerOffset goes into the body: the map's normal at A, turned inward if it points out
    sign = 1.0 if FreeCAD.Vector(*field.normal).dot(inward) > 0.0 else -1.0
    lattice = sl.becots_lattice(field, connectivity, counts, obj.NodeRadius.Value, layer_raise=obj.LayerRaise.Value,
                                beam_ratio=obj.BeamRatio, layer_offset=sign * obj.LayerOffset.Value)
    return field, lattice


def _screw_lattice(obj, cylinder, corners, inward, connectivity, counts, turns):
    """The lattice on a cylinder: U and V the screws about its axis taking A to D and A to B (whole turns added),
    one node template of the connectivity at the same radius everywhere, layers moved by LayerRaise along the axis
    and LayerOffset inward, first (order W U V, as becots_lattice)."""
    import steadylattice as sl
    a, b, d = corners
    axis, center = _unit(cylinder.Axis), cylinder.Center
    angle_u, angle_v = _about(axis, a - center, d - center), _about(axis, a - center, b - center)
    angle_u, angle_v = _with_turns(angle_u, angle_v, turns[0]), _with_turns(angle_v, angle_u, turns[1])
    rise_u, rise_v = (d - a).dot(axis), (b - a).dot(axis)
    nu, nv, _ = counts

    def screw(fraction_u, fraction_v):
        u = sl.Similarity.screw(fraction_u * angle_u, tuple(axis), tuple(center), fraction_u * rise_u)
        v = sl.Similarity.screw(fraction_v * angle_v, tuple(axis), tuple(center), fraction_v * rise_v)
        return u, v

    if isinstance(connectivity, str):
        connectivity = sl.becots_connectivity(connectivity)
    cells, patterns = connectivity
    radius, ratio = obj.NodeRadius.Value, obj.BeamRatio
    nodes = []
    for s, t in cells:
        u, v = screw(s / nu, t / nv)
        nodes.append((tuple(v.apply(u.apply(tuple(a)))), radius))
    beams = [tuple(p) + ((ratio * radius, ratio * radius) if ratio > 0.0 else ()) for p in patterns]
    step_u, step_v = screw(1.0 / nu, 1.0 / nv)
    layer = sl.Similarity.translation(tuple(axis * obj.LayerRaise.Value + inward * obj.LayerOffset.Value))
    lattice = sl.Lattice(nodes, beams, counts, step_u, step_v, layer, order="WUV")
    return ScrewField(angle_u, angle_v), lattice
