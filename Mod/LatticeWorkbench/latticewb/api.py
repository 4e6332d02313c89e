"""What a Python-console user or a macro calls.

    import FreeCAD
    from latticewb import api
    doc = FreeCAD.newDocument()
    lat = api.make_lattice(doc, preset="octet", cell_size=10, cells=(4, 4, 4), node_radius=1.2, beam_radius=0.8)
    doc.recompute()
    api.export([lat], "/tmp/octet.step")

This module only gathers the workbench's public functions; they live in their layers (make, kernel).
"""
__all__ = ["make_lattice", "make_curved_lattice", "make_part", "make_filter", "make_mesh", "properties",
           "target_density", "lattice", "ball_index_of",
           "export", "export_shape", "get_type"]

from latticewb.kernel import mass as _mass
from latticewb.kernel.export import export, export_shape  # noqa: F401
from latticewb.kernel.steady_lattice import lattice  # noqa: F401
from latticewb.make.make_curved import make_curved_lattice  # noqa: F401
from latticewb.make.make_filter import make_filter  # noqa: F401
from latticewb.make.make_lattice import make_lattice  # noqa: F401
from latticewb.make.make_mesh import make_mesh  # noqa: F401
from latticewb.make.make_part import make_part  # noqa: F401
from latticewb.utils import types as _types
from latticewb.utils.types import get_type  # noqa: F401


def properties(obj):
    """Mass properties of a SteadyLattice (closed form from the kernel) or of a part or any solid (B-rep
    integration): a dict with volume (mm^3), area (mm^2), centroid (mm), inertia (3x3 about the centroid, kg mm^2),
    mass (kg) and density (g/cm^3, the object's Density property, 1 when it has none), and the method used.
    A lattice whose hubs overlap is reported in the report view (which hubs) and measured as the exact union of
    the overlapping hubs ("overlaps" counts the pairs)."""
    return _mass.properties(obj)


def target_density(obj, relative_density=None, mass=None):
    """Scales every radius of a SteadyLattice so that it reaches a relative density (its volume over the volume of
    its box of cells) or a mass in kg (at its Density); returns the factor applied. Recompute to rebuild."""
    if not _types.is_lattice(obj):
        raise ValueError("obj: expected a SteadyLattice")
    scale = _mass.scale_for_target(obj, relative_density=relative_density, mass=mass)
    _mass.apply_radius_scale(obj, scale)
    return scale


def ball_index_of(obj, kernel_lattice, u, v, w, n):
    """Index into kernel_lattice.balls() of node n of the cell (u, v, w) counted along U, V, W (the kernel's
    indices count along U, V, W whatever the order the steps apply in)."""
    return kernel_lattice.ball_index(u, v, w, n)
