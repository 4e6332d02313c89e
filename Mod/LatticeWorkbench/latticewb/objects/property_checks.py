"""Checks of SteadyLattice properties as they change: nonsense is refused (the previous value comes back) or
clamped, always with a message in the report view, so that a recompute does not fail on a user's typo."""
import math

import FreeCAD

_MIN_TAPER = -99.0  # % per cell: a taper of -100 % would shrink a cell to nothing


def _message(obj, text):
    FreeCAD.Console.PrintWarning("%s: %s\n" % (obj.Label, text))


def _value(obj, prop):
    value = getattr(obj, prop)
    return value.Value if hasattr(value, "Value") else value


def _last_good(obj):
    """The last accepted value of each checked property, kept on the proxy (rebuilt as a document loads)."""
    proxy = obj.Proxy
    if not hasattr(proxy, "_last_good"):
        proxy._last_good = {}
    return proxy._last_good


def _refuse(obj, prop, why):
    good = _last_good(obj)
    if prop in good:
        _message(obj, "%s %s; keeping %r" % (prop, why, good[prop]))
        setattr(obj, prop, good[prop])
    else:
        _message(obj, "%s %s" % (prop, why))


def _beams_problem(obj):
    from latticewb.kernel.steady_lattice import parse_beam
    count = len(obj.Nodes)
    for index, text in enumerate(obj.Beams):
        try:
            n1, _, _, _, n2 = parse_beam(text, index)[:5]
        except ValueError as error:
            return str(error)
        for end in (n1, n2):
            if not 0 <= end < count:
                return "Beams[%d]: node %d does not exist (the template has %d nodes)" % (index, end, count)
    return None


def check_lattice_property(obj, prop):
    good = _last_good(obj)
    if prop in ("CellSize", "NodeRadius"):
        value = _value(obj, prop)
        if not (math.isfinite(value) and value > 0.0):
            return _refuse(obj, prop, "must be > 0 (got %g)" % value)
        if prop == "NodeRadius" and obj.BeamRadius.Value > value:
            _message(obj, "BeamRadius clamped to the new NodeRadius %g" % value)
            obj.BeamRadius = value
    elif prop == "BeamRadius":
        value = _value(obj, prop)
        if not (math.isfinite(value) and value >= 0.0):
            return _refuse(obj, prop, "must be >= 0 (got %g)" % value)
        if value > obj.NodeRadius.Value:
            _message(obj, "BeamRadius clamped to NodeRadius %g (a beam may not be wider than its node)"
                     % obj.NodeRadius.Value)
            obj.BeamRadius = obj.NodeRadius.Value
            return
    elif prop.startswith("Taper"):
        value = _value(obj, prop)
        if not math.isfinite(value):
            return _refuse(obj, prop, "must be a number")
        if value < _MIN_TAPER:
            _message(obj, "%s clamped to %g %% per cell (a cell cannot shrink to nothing)" % (prop, _MIN_TAPER))
            setattr(obj, prop, _MIN_TAPER)
            return
    elif prop.startswith(("Twist", "Bend")) and not prop.endswith("Toward"):
        if not math.isfinite(_value(obj, prop)):
            return _refuse(obj, prop, "must be a finite angle")
    elif prop == "NodeRadii":
        bad = [r for r in obj.NodeRadii if not (math.isfinite(r) and r > 0.0)]
        if bad:
            return _refuse(obj, prop, "must all be > 0 (got %g)" % bad[0])
    elif prop == "Beams":
        problem = _beams_problem(obj)
        if problem:
            return _refuse(obj, prop, "refused: " + problem)
    else:
        return
    good[prop] = getattr(obj, prop)
