"""Checks of the properties of the features made from a lattice (LatticeFilter, LatticePart and LatticeMesh) and of
the CurvedLattice.

property_checks applies them as it does the SteadyLattice's: nonsense is refused as it is set (the last good value
comes back, a warning names the property) and fails the recompute naming the property when it got in anyway.
Links are the exception: they are only checked at recompute, since FreeCAD itself empties a link when the linked
object is deleted, and bringing such a link back would point at nothing."""
import math

from latticewb.utils import types

_GYROID_RANGE = 1.5  # the gyroid field sin x cos y + ... stays within +-1.5: a wider bound keeps or drops everything
_MIN_SKIN = 1e-4  # mm: thinner walls are below what OpenCASCADE's offsets make (1e-300 "does not fit in the body")
_MAX_STENCIL_CELLS = 1000000  # one character per cell of the period: more is no mask anyone types

LINKS = ("Source", "Coarse", "Body", "Lattice")
CORNER_LINKS = ("ALink", "BLink", "CLink", "DLink")  # a CurvedLattice's vertices: (object, [sub-element])


def enumerations():
    """The values each enumeration of the three features may take; a Python console may replace the list itself
    (obj.Kind = ['a', 'b']), which FreeCAD accepts and the kernel would read as some other choice."""
    from latticewb.kernel.lattice_filter import GYROID_MODES, KINDS
    from latticewb.kernel.curved_lattice import CONNECTIVITIES
    from latticewb.kernel.lattice_part import DANGLING, POLICIES
    return {"Kind": KINDS, "GyroidMode": GYROID_MODES, "Policy": POLICIES, "Dangling": DANGLING,
            "Connectivity": CONNECTIVITIES}


def _length(obj, prop):
    value = getattr(obj, prop)
    return value.Value if hasattr(value, "Value") else value


def _max_coordinate():
    import steadylattice as sl
    return sl.MAX_COORDINATE


def _size_problem(value, what="length"):
    if not math.isfinite(value):
        return "must be a finite %s (got %g)" % (what, value)
    if value > _max_coordinate():
        return "is %g mm, beyond the supported range of %g mm (docs/design.md)" % (value, _max_coordinate())
    return None


def _depends_on(obj, target, seen=None):
    """Whether `obj` reaches `target` through the links these features follow (a cycle if target links obj)."""
    seen = set() if seen is None else seen
    if obj is None or obj.Name in seen:
        return False
    if obj == target:
        return True
    seen.add(obj.Name)
    return any(_depends_on(getattr(obj, name, None), target, seen) for name in LINKS
               if name in getattr(obj, "PropertiesList", ()))


def _link_problem(obj, prop):
    linked = getattr(obj, prop)
    if linked is None:
        return None  # said by the feature's own checks, which know whether the link is needed
    if linked == obj or _depends_on(linked, obj):
        return "%s links back to %s: a feature cannot be made from itself" % (linked.Label, obj.Label)
    return None


def _source_problem(obj, prop, needs):
    """A link to a lattice: `needs` is types.is_lattice (a SteadyLattice) or types.is_lattice_source (or a filter)."""
    linked = getattr(obj, prop)
    what = {types.is_lattice: "a SteadyLattice", types.is_part_lattice: "a SteadyLattice or a CurvedLattice"}.get(
        needs, "a SteadyLattice or a LatticeFilter")
    if linked is None:
        return "is empty: link %s" % what
    if not needs(linked):
        return "%s is not %s" % (linked.Label, what)
    return _link_problem(obj, prop)


def _body_problem(obj, one_solid):
    body = obj.Body
    if body is None:
        return "is empty: link a solid" if types.get_type(obj) == types.LATTICE_FILTER else None
    found = _link_problem(obj, "Body")
    if found:
        return found
    import Part
    shape = getattr(body, "Shape", None)
    if not isinstance(shape, Part.Shape) or shape.isNull():
        return "%s has no B-rep shape (a mesh or a plain object): link a solid" % body.Label
    solids = len(shape.Solids)
    if solids == 0:
        return "%s holds no solid (a closed solid is needed, not a face, shell or sketch)" % body.Label
    if one_solid and solids > 1:
        return "%s holds %d solids: link one solid" % (body.Label, solids)
    # A filter's body of several solids is their union; a face beside them (a loose face or open shell) bounds no
    # volume and would be ignored without a word.
    in_solids = {f.hashCode() for s in shape.Solids for f in s.Faces}
    loose = sum(1 for f in shape.Faces if f.hashCode() not in in_solids)
    if loose:
        return ("%s holds %d faces outside its solids (a loose face or open shell bounds no volume): link solids "
                "only" % (body.Label, loose))
    return None


def _filter_problem(obj, prop):
    if prop == "Source":
        return _source_problem(obj, prop, types.is_lattice_source)
    # Coarse and Body count for their kind only (a link left from another kind is harmless, unless a cycle)
    if prop == "Coarse":
        if obj.Kind != "lattice-in-lattice":
            return _link_problem(obj, prop) if obj.Coarse is not None else None
        return _source_problem(obj, prop, types.is_lattice_source)
    if prop == "Body":
        if obj.Kind != "inside body":
            return _link_problem(obj, prop) if obj.Body is not None else None
        return _body_problem(obj, False)
    if prop == "StencilSize":
        size = list(obj.StencilSize)
        if len(size) != 3 or min(size) < 1:
            return "give three periods >= 1 (got %s)" % size
        if size[0] * size[1] * size[2] > _MAX_STENCIL_CELLS:
            return "a period of %d cells is beyond %d (one mask character per cell)" % (
                size[0] * size[1] * size[2], _MAX_STENCIL_CELLS)
        return None
    if prop == "GyroidPeriod":
        period = _length(obj, prop)
        found = _size_problem(period)
        return found if found else (None if period > 0.0 else "must be > 0 (got %g)" % period)
    if prop == "GyroidThickness":
        t = obj.GyroidThickness
        low = 0.0 if obj.GyroidMode == "sheet" else -_GYROID_RANGE
        if not (math.isfinite(t) and low <= t <= _GYROID_RANGE):
            return ("must be within %g to %g for a %s, where the gyroid field lies (got %g): outside, the filter "
                    "keeps every node or none" % (low, _GYROID_RANGE, obj.GyroidMode, t))
        return None
    return None


def _part_problem(obj, prop):
    if prop == "Lattice":
        return _source_problem(obj, prop, types.is_part_lattice)
    if prop == "Body":
        return _body_problem(obj, True)
    if prop == "Skin":
        skin = _length(obj, prop)
        found = _size_problem(skin, "thickness")
        if found:
            return found
        if skin < 0.0:
            return "must be >= 0 (got %g; 0: no skin)" % skin
        if 0.0 < skin < _MIN_SKIN:
            return "a wall of %g mm is thinner than %g mm, too thin to offset; 0 for no skin" % (skin, _MIN_SKIN)
        return None
    return None


def _mesh_problem(obj, prop):
    if prop == "Lattice":
        return _source_problem(obj, prop, types.is_lattice)
    if prop == "Tolerance":
        tolerance = _length(obj, prop)
        found = _size_problem(tolerance)
        return found if found else (None if tolerance > 0.0 else "must be > 0 (got %g)" % tolerance)
    return None


def _curved_problem(obj, prop):
    if prop in ("A", "B", "C", "D"):
        p = getattr(obj, prop)
        for x in (p.x, p.y, p.z):
            found = _size_problem(abs(x), "coordinate")
            if found:
                return "corner %s %s" % (tuple(p), found)
        return None
    if prop in CORNER_LINKS:
        from latticewb.kernel.curved_lattice import linked_point
        try:
            linked_point(obj, prop[0])
        except ValueError as error:
            return str(error).partition(": ")[2]
        return None
    if prop == "NodeRadius":
        radius = _length(obj, prop)
        found = _size_problem(radius)
        return found if found else (None if radius > 0.0 else "must be > 0 (got %g)" % radius)
    if prop in ("LayerRaise", "LayerOffset"):
        return _size_problem(abs(_length(obj, prop)), "distance")
    if prop in ("TurnsU", "TurnsV"):
        from latticewb.kernel.curved_lattice import MAX_TURNS
        turns = getattr(obj, prop)
        return None if abs(turns) <= MAX_TURNS else "must be within +-%d whole turns (got %d)" % (MAX_TURNS, turns)
    if prop == "BeamRatio":
        ratio = obj.BeamRatio
        if not (math.isfinite(ratio) and 0.0 <= ratio <= 1.0):
            return "must lie in [0, 1] (got %g; 0: beams are the hulls of their balls)" % ratio
        return None
    return None


_PROBLEMS = {types.LATTICE_FILTER: _filter_problem, types.LATTICE_PART: _part_problem,
             types.LATTICE_MESH: _mesh_problem, types.CURVED_LATTICE: _curved_problem}


def problem(obj, prop):
    """What is wrong with `prop` of a LatticeFilter, LatticePart or LatticeMesh (None: nothing, or not checked)."""
    allowed = enumerations().get(prop)
    if allowed is not None and getattr(obj, prop) not in allowed:
        return "must be one of %s (got %r)" % (", ".join(allowed), getattr(obj, prop))
    check = _PROBLEMS.get(types.get_type(obj))
    return check(obj, prop) if check else None


def refused_when_set(obj, prop):
    """Whether a nonsense value of prop is refused as it is set: every property but links, and links that make
    a cycle (FreeCAD would not recompute the feature at all, so no error would name the link)."""
    if prop in CORNER_LINKS:
        return False  # a vertex that went away with an edit of its sketch: said at recompute
    return prop not in LINKS or _link_problem(obj, prop) is not None


def checked(obj):
    """Whether these checks (rather than the SteadyLattice's) apply to obj."""
    return types.get_type(obj) in _PROBLEMS


def restore(obj, prop, good):
    """Sets a refused property back to its last good value; an enumeration gets its list of choices back first."""
    allowed = enumerations().get(prop)
    if allowed is not None:
        setattr(obj, prop, list(allowed))
    setattr(obj, prop, good)


# What the kernel names after its own parameters, for the errors only it can find (a skin thicker than the body,
# a tolerance against the balls' radii): the property the user set.
_KERNEL_NAMES = {"skin": "Skin", "tolerance": "Tolerance", "body": "Body", "policy": "Policy",
                 "dangling": "Dangling"}


def named_kernel_error(error):
    """The kernel's message with its parameter name replaced by the property's ('skin: ...' -> 'Skin: ...')."""
    text = str(error)
    head, sep, rest = text.partition(": ")
    return _KERNEL_NAMES[head] + sep + rest if sep and head in _KERNEL_NAMES else text
