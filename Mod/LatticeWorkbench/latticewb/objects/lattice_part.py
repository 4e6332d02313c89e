"""LatticePart: a steady lattice trimmed into a body, optionally with a skin, as one exact B-rep solid.

Links to a SteadyLattice (or a CurvedLattice) and to a body (any object whose Shape holds a closed solid: a Part
primitive, a PartDesign Body, an imported STEP part). The kernel classifies every hub against the body, keeps inside
hubs whole, drops outside ones and cuts only the crossing hubs (policy clip), keeps only hubs whole inside (whole),
or those joined to the wall by bridges, beams from each kept hub that lost a neighbour to the nearest point of the
wall (bridge); with a skin, the body's wall of that thickness is united with the lattice trimmed to the inner
offset. Editing the lattice or the body re-trims the part.

Trimming shows FreeCAD's progress bar (and, when it lasts, a dialog with a Cancel button). A cancelled recompute
keeps the previous shape and leaves the part touched (needing recompute), with a warning in the report view.
"""
import FreeCAD
import Part

from latticewb.kernel.lattice_part import DANGLING, POLICIES, part_brep
from latticewb.objects import density, feature_checks, property_checks
from latticewb.utils import types
from latticewb.utils.proxies import StatelessProxy, add_missing_properties

_PROPERTIES = [
    ("App::PropertyLink", "Lattice", "Part", "The SteadyLattice or CurvedLattice to trim"),
    ("App::PropertyLink", "Body", "Part", "The solid the lattice fills (empty: the whole lattice as one part)"),
    ("App::PropertyEnumeration", "Policy", "Part",
     "clip: cut the lattice at the body's boundary; whole: keep only hubs entirely inside, never cut; bridge: the "
     "hubs whole keeps, each that lost a neighbour joined to the wall (or skin) by a beam to its nearest point"),
    ("App::PropertyEnumeration", "Dangling", "Part",
     "keep or remove the beams that join a kept hub to a dropped one (bridge: always replaced by bridges)"),
    ("App::PropertyLength", "Skin", "Part",
     "Wall thickness of a skin (the body's inward offset) united with the lattice; 0: no skin"),
    ("App::PropertyFloat", "Volume", "Result", "Volume of the part in mm^3 (read only)"),
    ("App::PropertyInteger", "FaceCount", "Result", "Faces of the part's B-rep (read only)"),
]


class LatticePart(StatelessProxy):
    Type = types.LATTICE_PART

    def __init__(self, obj):
        obj.Proxy = self
        self.ensure_properties(obj)

    @staticmethod
    def ensure_properties(obj):
        fresh = add_missing_properties(obj, _PROPERTIES)
        if "Policy" in fresh:
            obj.Policy = POLICIES
            obj.Policy = "clip"
        if "Dangling" in fresh:
            obj.Dangling = DANGLING
            obj.Dangling = "keep"
        for name in ("Volume", "FaceCount"):
            obj.setEditorMode(name, 1)
        density.add_density_property(obj)
        property_checks.remember_good(obj)

    def onDocumentRestored(self, obj):
        self.ensure_properties(obj)

    def onChanged(self, obj, prop):
        if hasattr(obj, "Density"):  # the last property: not while ensure_properties adds them
            property_checks.check_lattice_property(obj, prop)

    def execute(self, obj):
        import steadylattice
        from latticewb.utils import progress
        stats = {}
        try:
            property_checks.require_sensible(obj)  # names the property, where the kernel would name its own fields
            with progress.LongOperation("Trimming %s" % obj.Label) as report:
                text = part_brep(obj, report, stats)
        except ValueError as error:
            error = feature_checks.named_kernel_error(error)
            FreeCAD.Console.PrintError("%s: %s\n" % (obj.Label, error))
            raise ValueError("%s: %s" % (obj.Label, error)) from None
        except steadylattice.Cancelled:
            progress.keep_previous_shape(obj, "trimming")
            return
        shape = Part.Shape()
        shape.importBrepFromString(text)
        obj.Shape = shape
        # the kernel's integration by Green's theorem on each face: Shape.Volume's fixed Gauss rule is 1e-3 off on
        # crowded spheres
        obj.Volume = stats.get("volume") or shape.Volume
        obj.FaceCount = len(shape.Faces)
        property_checks.remember_good(obj)
        report_trim(obj.Label, stats)


def report_trim(label, stats):
    """Tells the report view what the user should know about a trim: Booleans that are exact only to a
    tolerance (a warning), and the retries and fallbacks OpenCASCADE needed (messages)."""
    if not stats:
        return
    if stats["fuzzy_clusters"]:
        FreeCAD.Console.PrintWarning(
            "%s: %d boundary cluster(s) of %d were clipped with a fuzzy Boolean (OpenCASCADE failed the exact one "
            "where the body's surface grazes the lattice): the part is exact there only to 1e-4 to 1e-3 of a "
            "hub's size\n" % (label, stats["fuzzy_clusters"], stats["band_clusters"]))
    retried = stats["retried_clusters"] - stats["fuzzy_clusters"]
    if retried > 0:
        FreeCAD.Console.PrintMessage(
            "%s: %d boundary cluster(s) clipped exactly on a second try (other layout, turned frame, or %d with the "
            "thin bands of cone between crowded hubs' collars merged into their stumps)\n"
            % (label, retried, stats.get("merged_clusters", 0)))
    if stats["relaid_out"]:
        FreeCAD.Console.PrintMessage("%s: trimmed on a later attempt, the first having failed (%s)\n"
                                     % (label, stats["relaid_reason"]))
    if stats.get("rerouted_bridges"):
        FreeCAD.Console.PrintMessage(
            "%s: %d of %d bridges took another route to the wall (toward the nearest point they would run into "
            "another kept element)\n" % (label, stats["rerouted_bridges"], stats["bridges"]))
    if stats.get("blocked_bridges"):
        FreeCAD.Console.PrintWarning(
            "%s: %d of %d hubs that lost a neighbour got no bridge (on every route tried it would run into another "
            "kept element); they stay joined by their other beams\n"
            % (label, stats["blocked_bridges"], stats["lost_neighbour_hubs"]))
    if stats.get("rim_cut_reason"):
        FreeCAD.Console.PrintMessage(
            "%s: the clusters on the skin's rims were clipped one by one, their single Cut having failed (%s)\n"
            % (label, stats["rim_cut_reason"]))
    if stats["union_through_pores"]:
        FreeCAD.Console.PrintMessage("%s: the union with the skin went through the pores (%s)\n"
                                     % (label, stats["pores_reason"]))
