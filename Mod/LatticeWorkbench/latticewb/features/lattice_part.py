"""LatticePart: a steady lattice trimmed into a body, optionally with a skin, as one exact B-rep solid.

Links to a SteadyLattice and to a body (any object whose Shape holds a closed solid: a Part primitive, a PartDesign
Body, an imported STEP part). The kernel classifies every hub against the body, keeps inside hubs whole, drops
outside ones and cuts only the crossing hubs; with a skin, the body's wall of that thickness is united with the
lattice trimmed to the inner offset. Editing the lattice or the body re-trims the part.

Trimming shows FreeCAD's progress bar (and, when it lasts, a dialog with a Cancel button). A cancelled recompute
keeps the previous shape and leaves the part touched (needing recompute), with a warning in the report view.
"""
import FreeCAD
import Part

from latticewb.proxies import StatelessProxy, add_missing_properties

POLICIES = ["clip", "whole"]
DANGLING = ["keep", "remove"]

_PROPERTIES = [
    ("App::PropertyLink", "Lattice", "Part", "The SteadyLattice to trim"),
    ("App::PropertyLink", "Body", "Part", "The solid the lattice fills (empty: the whole lattice as one part)"),
    ("App::PropertyEnumeration", "Policy", "Part",
     "clip: cut the lattice at the body's boundary; whole: keep only hubs entirely inside, never cut"),
    ("App::PropertyEnumeration", "Dangling", "Part",
     "keep or remove the beams that join a kept hub to a dropped one"),
    ("App::PropertyLength", "Skin", "Part",
     "Wall thickness of a skin (the body's inward offset) united with the lattice; 0: no skin"),
    ("App::PropertyFloat", "Volume", "Result", "Volume of the part in mm^3 (read only)"),
    ("App::PropertyInteger", "FaceCount", "Result", "Faces of the part's B-rep (read only)"),
]


class LatticePart(StatelessProxy):
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
        from latticewb.features import mass_properties
        mass_properties.add_density_property(obj)

    def onDocumentRestored(self, obj):
        self.ensure_properties(obj)

    def onChanged(self, obj, prop):
        if prop == "Skin" and hasattr(obj, "Skin") and obj.Skin.Value < 0.0:
            FreeCAD.Console.PrintWarning("%s: Skin must be >= 0 (got %g); set to 0\n" % (obj.Label, obj.Skin.Value))
            obj.Skin = 0.0

    def execute(self, obj):
        import steadylattice
        from latticewb import progress
        stats = {}
        try:
            with progress.LongOperation("Trimming %s" % obj.Label) as report:
                text = part_brep(obj, report, stats)
        except ValueError as error:
            FreeCAD.Console.PrintError("%s: %s\n" % (obj.Label, error))
            raise ValueError("%s: %s" % (obj.Label, error)) from None
        except steadylattice.Cancelled:
            progress.keep_previous_shape(obj, "trimming")
            return
        shape = Part.Shape()
        shape.importBrepFromString(text)
        obj.Shape = shape
        obj.Volume = shape.Volume
        obj.FaceCount = len(shape.Faces)
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
            "%s: %d boundary cluster(s) clipped exactly on a second try (other layout or turned frame)\n"
            % (label, retried))
    if stats["relaid_out"]:
        FreeCAD.Console.PrintMessage("%s: trimmed on a later attempt, the first having failed (%s)\n"
                                     % (label, stats["relaid_reason"]))
    if stats["union_through_pores"]:
        FreeCAD.Console.PrintMessage("%s: the union with the skin went through the pores (%s)\n"
                                     % (label, stats["pores_reason"]))


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
    from latticewb import api
    if obj.Lattice is None:
        raise ValueError("Lattice: link a SteadyLattice to trim")
    if not hasattr(obj.Lattice, "Preset"):
        raise ValueError("Lattice: %s is not a SteadyLattice" % obj.Lattice.Label)
    return api.lattice(obj.Lattice), body_brep(obj), obj.Policy, obj.Skin.Value, obj.Dangling


def part_brep(obj, report=None, stats=None):
    """BREP text of the part. report(fraction) -> False cancels (steadylattice.Cancelled, nothing changed);
    stats: None or a dict the kernel fills with how the trim went (see steadylattice.Lattice.brep)."""
    lattice, body, policy, skin, dangling = kernel_request(obj)
    if skin > 0.0 and body is None:
        raise ValueError("Skin: a skin needs a Body")
    return lattice.brep(body, policy, skin, dangling, progress=report, stats=stats)


def write_step_assembly(obj, path, report=None):
    """STEP with the skin and the lattice as two named, coloured parts (the kernel's XCAF writer).
    report(fraction) -> False cancels (steadylattice.Cancelled; the file is not written)."""
    lattice, body, policy, skin, dangling = kernel_request(obj)
    lattice.write_step(path, body, policy, skin, dangling, lattice_name=obj.Label + " lattice",
                       skin_name=obj.Label + " skin", progress=report)


def make_lattice_part(doc, lattice, body=None, policy="clip", skin=0.0, dangling="keep", name="LatticePart"):
    obj = doc.addObject("Part::FeaturePython", name)
    LatticePart(obj)
    obj.Lattice = lattice
    obj.Body = body
    obj.Policy = policy
    obj.Skin = skin
    obj.Dangling = dangling
    if FreeCAD.GuiUp:
        from latticewb.gui import view_providers
        view_providers.ViewProviderLatticePart(obj.ViewObject)
        lattice.ViewObject.Visibility = False
        if body is not None:
            body.ViewObject.Visibility = False
    return obj
