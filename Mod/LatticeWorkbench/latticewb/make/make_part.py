"""make_part: a LatticePart (a lattice trimmed into a body), and its view provider when the GUI is up."""
import FreeCAD

from latticewb.kernel.lattice_part import DANGLING, POLICIES
from latticewb.objects.lattice_part import LatticePart
from latticewb.utils import types


def make_part(doc, lattice, body=None, policy="clip", skin=0.0, dangling="keep"):
    """Adds a LatticePart: `lattice` (a SteadyLattice or a CurvedLattice) trimmed into `body` (an object with a solid
    Shape, or None for the whole lattice) as one exact B-rep solid. policy: "clip" (cut at the boundary), "whole"
    (only hubs entirely inside) or "bridge" (those hubs, each that lost a neighbour joined to the wall by a bridge
    beam toward its nearest point); skin: wall thickness of the body's skin united with the lattice (0: none);
    dangling: "keep" or "remove" beams joining a kept hub to a dropped one. Recompute the document to build it."""
    if policy not in POLICIES:
        raise ValueError("policy: expected one of %s (got %r)" % (", ".join(POLICIES), policy))
    if dangling not in DANGLING:
        raise ValueError("dangling: expected one of %s (got %r)" % (", ".join(DANGLING), dangling))
    if not skin >= 0.0:
        raise ValueError("skin: must be >= 0 (got %r)" % (skin,))
    if not types.is_part_lattice(lattice):
        raise ValueError("lattice: expected a SteadyLattice or CurvedLattice object")
    obj = doc.addObject("Part::FeaturePython", "LatticePart")
    LatticePart(obj)
    obj.Lattice = lattice
    obj.Body = body
    obj.Policy = policy
    obj.Skin = skin
    obj.Dangling = dangling
    if FreeCAD.GuiUp:
        from latticewb.viewproviders import view_providers
        view_providers.ViewProviderLatticePart(obj.ViewObject)
        lattice.ViewObject.Visibility = False
        if body is not None:
            body.ViewObject.Visibility = False
    return obj
