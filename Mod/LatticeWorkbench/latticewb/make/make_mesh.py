"""make_mesh: a LatticeMesh (a lattice as a FreeCAD mesh, straight from the kernel)."""
import math

import FreeCAD

from latticewb.objects.lattice_mesh import LatticeMesh
from latticewb.utils import types


def make_mesh(doc, lattice, tolerance=0.01):
    """Adds a LatticeMesh of `lattice` (a SteadyLattice) at `tolerance` mm of chord error (every triangle within it
    of the exact surface). Recompute the document to build it."""
    if not types.is_lattice(lattice):
        raise ValueError("lattice: expected a SteadyLattice object")
    if not (isinstance(tolerance, (int, float)) and math.isfinite(tolerance) and tolerance > 0.0):
        raise ValueError("tolerance: must be a length > 0 (got %r)" % (tolerance,))
    obj = doc.addObject("Mesh::FeaturePython", "LatticeMesh")
    LatticeMesh(obj)
    obj.Lattice = lattice
    obj.Tolerance = tolerance
    if FreeCAD.GuiUp:
        from latticewb.viewproviders import view_providers
        view_providers.ViewProviderLatticeMesh(obj.ViewObject)
        lattice.ViewObject.Visibility = False
    return obj
