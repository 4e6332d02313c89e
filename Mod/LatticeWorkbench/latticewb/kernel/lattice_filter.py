"""A LatticeFilter object's kernel filter and filtered lattice (a cascade of filters is the conjunction of their
filters on the base lattice)."""
from latticewb.kernel import steady_lattice
from latticewb.utils import types

KINDS = ["stencil", "lattice-in-lattice", "gyroid", "inside body"]
GYROID_MODES = ["sheet", "solid"]


def _stencil(obj):
    import numpy as np
    import steadylattice as sl
    size = list(obj.StencilSize)
    if len(size) != 3 or min(size) < 1:
        raise ValueError("StencilSize: give three periods >= 1 (got %s)" % size)
    mask = obj.StencilMask.replace(" ", "")
    if len(mask) != size[0] * size[1] * size[2] or set(mask) - {"0", "1"}:
        raise ValueError("StencilMask: give %d characters 0 or 1 (one per cell of the %dx%dx%d period, i fastest)"
                         % (size[0] * size[1] * size[2], size[0], size[1], size[2]))
    cells = np.array([c == "1" for c in mask], dtype=bool).reshape(size[2], size[1], size[0])
    return sl.IndexStencil(np.ascontiguousarray(cells.transpose(2, 1, 0)))


def node_filter(obj):
    """The steadylattice.Filter of this LatticeFilter alone (without its source's)."""
    import steadylattice as sl
    if obj.Kind == "stencil":
        f = _stencil(obj)
    elif obj.Kind == "lattice-in-lattice":
        if not types.is_lattice_source(obj.Coarse):
            raise ValueError("Coarse: link the coarse lattice (a SteadyLattice or LatticeFilter)")
        f = sl.LatticeInLattice(filtered_lattice(obj.Coarse))
    elif obj.Kind == "gyroid":
        if not obj.GyroidPeriod.Value > 0.0:
            raise ValueError("GyroidPeriod: must be > 0")
        f = sl.Gyroid(obj.GyroidPeriod.Value, obj.GyroidThickness, (0.0, 0.0, 0.0), obj.GyroidMode)
    else:
        if obj.Body is None or not obj.Body.Shape.Solids:
            raise ValueError("Body: link a solid")
        f = sl.InsideBody(obj.Body.Shape.exportBrepToString())
    return ~f if obj.Invert else f


def filtered_lattice(obj):
    """A steadylattice.FilteredLattice (placed in the document's coordinates) of a SteadyLattice or LatticeFilter;
    a cascade of filters is the conjunction of their filters on the base lattice."""
    import steadylattice as sl
    if types.is_lattice(obj):
        return sl.FilteredLattice(steady_lattice.lattice(obj))
    if not types.is_lattice_source(obj.Source):
        raise ValueError("Source: link a SteadyLattice or another LatticeFilter")
    if obj.Source == obj or obj.Coarse == obj:
        raise ValueError("Source: a filter cannot filter itself")
    source = filtered_lattice(obj.Source)
    own = node_filter(obj)
    combined = own if source.filter is None else source.filter & own
    return sl.FilteredLattice(source.lattice, combined)
