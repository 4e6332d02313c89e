"""Checks of SteadyLattice properties: one check per kind of property says what is wrong with its value. The
features made from a lattice (LatticeFilter, LatticePart, LatticeMesh) go through the same mechanism with their own
checks (feature_checks).

The same checks act twice. As a value is set, nonsense is refused (the previous good value comes back) or clamped,
with a message in the report view, so that a typo does not break the object. At recompute, a value that got in
anyway (a document from an older version, a value set before any good one was known) fails the object with an
error naming the property, before the kernel sees it and names its own internal fields instead."""
import math

import FreeCAD

from latticewb.objects import feature_checks

_MIN_TAPER = -99.0  # % per cell: a taper of -100 % would shrink a cell to nothing
_MAX_OFFSET = 1000000  # a beam pattern's cell offset: no lattice has more cells along a direction


def _message(obj, text):
    FreeCAD.Console.PrintWarning("%s: %s\n" % (obj.Label, text))


def _value(obj, prop):
    value = getattr(obj, prop)
    return value.Value if hasattr(value, "Value") else value


def _max_coordinate():
    import steadylattice as sl
    return sl.MAX_COORDINATE


def _length_problem(value, positive):
    """What is wrong with a length in mm (None: nothing)."""
    if not math.isfinite(value):
        return "must be a finite length (got %g)" % value
    if positive and not value > 0.0:
        return "must be > 0 (got %g)" % value
    if not value >= 0.0:
        return "must be >= 0 (got %g)" % value
    if value > _max_coordinate():
        return "is %g mm, beyond the supported range of %g mm (docs/design.md)" % (value, _max_coordinate())
    return None


def _point_problem(vector, what):
    for c in (vector.x, vector.y, vector.z):
        if not math.isfinite(c):
            return "%s must be finite (got %s)" % (what, tuple(vector))
        if abs(c) > _max_coordinate():
            return "%s %s is beyond the supported range of +-%g mm" % (what, tuple(vector), _max_coordinate())
    return None


def _placement_problem(placement):
    q = placement.Rotation.Q
    if not all(math.isfinite(x) for x in q):
        return "its rotation must be finite (got the quaternion %s)" % (tuple(q),)
    return _point_problem(placement.Base, "its position")


def _beams_problem(obj):
    from latticewb.kernel.steady_lattice import CUSTOM, parse_beam
    # A preset's beams come from the preset: Beams is then only what 'custom' will start from, checked for form.
    count = len(obj.Nodes) if obj.Preset == CUSTOM else None
    for index, text in enumerate(obj.Beams):
        try:
            fields = parse_beam(text, index)
        except ValueError as error:
            return str(error)
        n1, di, dj, dk, n2 = fields[:5]
        for d in (di, dj, dk):
            if abs(d) > _MAX_OFFSET:
                return "Beams[%d]: the cell offset %d is beyond +-%d" % (index, d, _MAX_OFFSET)
        for end in (n1, n2):
            if count is not None and not 0 <= end < count:
                return "Beams[%d]: node %d does not exist (the template has %d nodes)" % (index, end, count)
            if end < 0:
                return "Beams[%d]: node %d does not exist" % (index, end)
        for r in fields[5:]:
            problem = _length_problem(r, False)
            if problem:
                return "Beams[%d]: an end radius %s" % (index, problem)
    return None


def _density_problem(obj):
    value = obj.Density
    return None if math.isfinite(value) and value > 0.0 else "must be a finite density > 0 g/cm^3 (got %g)" % value


def problem(obj, prop):
    """What is wrong with the value of `prop` (None: nothing, or a property these checks do not cover)."""
    if prop == "Density":
        return _density_problem(obj)
    if feature_checks.checked(obj):
        return feature_checks.problem(obj, prop)
    if prop in ("CellSize", "NodeRadius"):
        return _length_problem(_value(obj, prop), True)
    if prop == "BeamRadius":
        return _length_problem(_value(obj, prop), False)
    if prop.startswith("Taper"):
        return None if math.isfinite(_value(obj, prop)) else "must be a number"
    if prop.startswith(("Twist", "Bend")) and not prop.endswith("Toward"):
        return None if math.isfinite(_value(obj, prop)) else "must be a finite angle"
    if prop.startswith(("Scale", "EndScale")):
        value = _value(obj, prop)
        return None if math.isfinite(value) and value > 0.0 else "must be a finite scale > 0 (got %g)" % value
    if prop == "Placement" or (prop.startswith(("Step", "End")) and prop not in ("StepMode",)
                               and not prop.startswith("EndScale")):
        return _placement_problem(getattr(obj, prop))
    if prop == "NodeRadii":
        for r in obj.NodeRadii:
            found = _length_problem(r, True)
            if found:
                return "must all be > 0 and finite: %s" % found
        return None
    if prop == "Nodes":
        for index, v in enumerate(obj.Nodes):
            found = _point_problem(v, "node %d" % index)
            if found:
                return found
        return None
    if prop == "Beams":
        return _beams_problem(obj)
    return None


def _span_problem(obj):
    """Values fine one by one whose product is not: the lattice's extent, its growth and its turning."""
    from latticewb.kernel.steady_lattice import cell_aspect
    import steadylattice as sl
    for axis, aspect in zip("UVW", cell_aspect(obj)):
        cells = getattr(obj, "Cells" + axis) + 1
        span = obj.CellSize.Value * aspect * cells
        if span > sl.MAX_COORDINATE:
            return ("CellSize", "%g mm over %d cells along %s spans %g mm, beyond the supported range of %g mm"
                    % (obj.CellSize.Value, cells, axis, span, sl.MAX_COORDINATE))
        if obj.Layout != "grading":
            continue
        growth = abs(math.log1p(getattr(obj, "Taper" + axis) / 100.0)) * cells
        if growth > sl.MAX_LOG_SCALE:
            return ("Taper" + axis, "%g %% per cell over %d cells scales by e^%g, beyond the supported e^%g"
                    % (getattr(obj, "Taper" + axis), cells, growth, sl.MAX_LOG_SCALE))
        for kind in ("Twist", "Bend"):
            turn = abs(math.radians(getattr(obj, kind + axis).Value)) * cells
            if turn > sl.MAX_ANGLE:
                return (kind + axis, "%g degrees per cell over %d cells turns %g rad, beyond the supported %g rad"
                        % (getattr(obj, kind + axis).Value, cells, turn, sl.MAX_ANGLE))
    return None


def _named(prop, why):
    """'Prop: why', unless the text already starts with the property (Beams[2]: ...)."""
    return why if why.startswith(prop) else "%s: %s" % (prop, why)


def require_sensible(obj):
    """Raises ValueError naming the first property whose value (or whose product with others) is nonsense."""
    for prop in obj.PropertiesList:
        found = problem(obj, prop)
        if found:
            raise ValueError(_named(prop, found))
    found = _span_problem(obj) if not feature_checks.checked(obj) else None
    if found:
        raise ValueError(_named(*found))


def _last_good(obj):
    """The last accepted value of each checked property, kept on the proxy (not saved: seeded again as a document
    loads and after every successful recompute)."""
    proxy = obj.Proxy
    if not hasattr(proxy, "_last_good"):
        proxy._last_good = {}
    return proxy._last_good


# Properties no refusal restores (the result, and FreeCAD's own bookkeeping).
_NOT_RESTORED = ("Label", "Label2", "Shape", "Mesh", "Proxy", "ExpressionEngine", "Visibility", "AppliedOrder",
                 "BallCount", "BeamCount", "Volume", "FaceCount", "TriangleCount", "DistinctHubs")


def remember_good(obj):
    """Records every property's current value that passes its check: what a later refusal restores."""
    good = _last_good(obj)
    for prop in obj.PropertiesList:
        if prop not in _NOT_RESTORED and problem(obj, prop) is None:
            good[prop] = getattr(obj, prop)


def _refuse(obj, prop, why):
    good = _last_good(obj)
    if prop in good:
        _message(obj, "%s; keeping %r" % (_named(prop, why), good[prop]))
        feature_checks.restore(obj, prop, good[prop])
    else:
        _message(obj, _named(prop, why))


def _clamp(obj, prop):
    """Clamps a value that is sensible in kind but out of range; True when it did (the clamp set it again)."""
    if prop == "NodeRadius" and obj.BeamRadius.Value > obj.NodeRadius.Value:
        _message(obj, "BeamRadius clamped to the new NodeRadius %g" % obj.NodeRadius.Value)
        obj.BeamRadius = obj.NodeRadius.Value
    elif prop == "BeamRadius" and obj.BeamRadius.Value > obj.NodeRadius.Value:
        _message(obj, "BeamRadius clamped to NodeRadius %g (a beam may not be wider than its node)"
                 % obj.NodeRadius.Value)
        obj.BeamRadius = obj.NodeRadius.Value
        return True
    elif prop.startswith("Taper") and _value(obj, prop) < _MIN_TAPER:
        _message(obj, "%s clamped to %g %% per cell (a cell cannot shrink to nothing)" % (prop, _MIN_TAPER))
        setattr(obj, prop, _MIN_TAPER)
        return True
    return False


def check_lattice_property(obj, prop):
    """onChanged: refuses nonsense (the last good value comes back) or clamps it, with a message."""
    found = problem(obj, prop)
    if found and feature_checks.refused_when_set(obj, prop):
        return _refuse(obj, prop, found)
    if found:
        return  # a link: said at recompute
    if not feature_checks.checked(obj) and _clamp(obj, prop):  # the clamps are the SteadyLattice's
        return
    if prop not in _NOT_RESTORED and prop in obj.PropertiesList:
        _last_good(obj)[prop] = getattr(obj, prop)
