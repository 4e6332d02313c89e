"""A LatticePart object's kernel work: the lattice trimmed into its body (with a skin), as BREP text or as a
STEP assembly of the skin and the lattice."""
import FreeCAD

from latticewb.kernel import curved_lattice, steady_lattice
from latticewb.utils import types

POLICIES = ["clip", "whole", "bridge"]
DANGLING = ["keep", "remove"]


def _log(message):
    """The kernel's diagnostics of a trim go to FreeCAD's log (Edit > Preferences > Report view > Log)."""
    FreeCAD.Console.PrintLog(message + "\n")


def body_brep(obj):
    """BREP text of the part's body, in global coordinates, or None without a body."""
    if obj.Body is None:
        return None
    shape = obj.Body.Shape
    if shape.isNull() or not shape.Solids:
        raise ValueError("Body: %s holds no solid to fill (a closed solid is needed)" % obj.Body.Label)
    return shape.exportBrepToString()


def kernel_request(obj):
    """(placed steadylattice.Lattice, body BREP or None, policy, skin, dangling) of a LatticePart."""
    if obj.Lattice is None:
        raise ValueError("Lattice: link a SteadyLattice or a CurvedLattice to trim")
    if not types.is_part_lattice(obj.Lattice):
        raise ValueError("Lattice: %s is not a SteadyLattice or a CurvedLattice" % obj.Lattice.Label)
    source = curved_lattice if types.is_curved_lattice(obj.Lattice) else steady_lattice
    return source.lattice(obj.Lattice), body_brep(obj), obj.Policy, obj.Skin.Value, obj.Dangling


def part_brep(obj, report=None, stats=None):
    """BREP text of the part. report(fraction) -> False cancels (steadylattice.Cancelled, nothing changed);
    stats: None or a dict the kernel fills with how the trim went (see steadylattice.Lattice.brep)."""
    lattice, body, policy, skin, dangling = kernel_request(obj)
    if skin > 0.0 and body is None:
        raise ValueError("Skin: a skin needs a Body")
    return lattice.brep(body, policy, skin, dangling, progress=report, stats=stats, log=_log)


def write_step_assembly(obj, path, report=None, united=False):
    """STEP with the skin and the lattice as two named, coloured parts (the kernel's XCAF writer); with `united`
    one part named as the object, the lattice united with its skin (its Shape).
    report(fraction) -> False cancels (steadylattice.Cancelled; the file is not written).
    Returns the trim's stats (a dict; skin_pieces: pieces of the lattice written as part of the skin, those that
    touch only the skin and, grazing_pieces of them, the lenses of beams whose axis runs in the skin)."""
    lattice, body, policy, skin, dangling = kernel_request(obj)
    stats = {}
    lattice_name = obj.Label if united else obj.Label + " lattice"
    lattice.write_step(path, body, policy, skin, dangling, lattice_name=lattice_name, skin_name=obj.Label + " skin",
                       progress=report, stats=stats, united=united)
    if stats.get("skin_pieces") and not united:
        FreeCAD.Console.PrintMessage(
            "%s: %d pieces of the lattice (%.4g mm^3) are part of \"%s skin\" in %s: %d that touch only the skin "
            "and %d lenses of beams whose axis runs in the skin but which dip through its inner wall\n"
            % (obj.Label, stats["skin_pieces"], stats["skin_pieces_volume"], obj.Label, path,
               stats["skin_pieces"] - stats["grazing_pieces"], stats["grazing_pieces"]))
    if stats.get("kept_straddling_faces"):  # faces the kernel could not lay out anew: never silent
        FreeCAD.Console.PrintWarning(
            "%s: %d sphere faces in %s keep a loop across their seam (%s); STEP readers may find them invalid\n"
            % (obj.Label, stats["kept_straddling_faces"], path, stats["kept_straddling_reason"]))
    return stats
