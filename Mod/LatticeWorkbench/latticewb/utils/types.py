"""Type tags of the workbench's document objects, as FreeCAD's Draft workbench does it: every proxy class carries
`Type`, and `get_type(obj)` reads it (from the object's proxy, so documents saved before the tag existed are
recognised too: their proxies are instances of the same classes)."""

STEADY_LATTICE = "SteadyLattice"
LATTICE_FILTER = "LatticeFilter"
LATTICE_PART = "LatticePart"
LATTICE_MESH = "LatticeMesh"
CURVED_LATTICE = "CurvedLattice"


def get_type(obj):
    """The workbench type tag of `obj` ("SteadyLattice", "LatticeFilter", "LatticePart", "LatticeMesh",
    "CurvedLattice"), or None."""
    proxy = getattr(obj, "Proxy", None) if obj is not None else None
    return getattr(proxy, "Type", None)


def is_lattice(obj):
    return get_type(obj) == STEADY_LATTICE


def is_curved_lattice(obj):
    return get_type(obj) == CURVED_LATTICE


def is_part_lattice(obj):
    """A lattice a LatticePart can trim: a SteadyLattice or a CurvedLattice."""
    return get_type(obj) in (STEADY_LATTICE, CURVED_LATTICE)


def is_lattice_source(obj):
    """A lattice a filter or a part can take: a SteadyLattice or a LatticeFilter."""
    return get_type(obj) in (STEADY_LATTICE, LATTICE_FILTER)


def is_part(obj):
    return get_type(obj) == LATTICE_PART


def is_mesh(obj):
    return get_type(obj) == LATTICE_MESH
