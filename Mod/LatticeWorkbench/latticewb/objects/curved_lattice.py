"""CurvedLattice: a BeCOTS lattice (docs/cots.md) laid on the field through four corners, usable without the GUI.

The corners A = M(0,0), B = M(0,1), C = M(1,1), D = M(1,0) are typed in the property editor, or taken from linked
vertices (ALink .. DLink: a sketch's point, a Draft point, a vertex of a Part shape), which then win over the typed
values. Four coplanar corners give a planar (COTS) sheet; others roll the sheet onto the cone the field follows.
The lattice has CellsU x CellsV groups of the chosen connectivity per layer, Layers layers raised by LayerRaise
along the field's axis and offset by LayerOffset along the sheet's normal at A (JoinLayers: each node joined to its copy in the next layer). It is an ordinary lattice to
the kernel, so a LatticePart trims it like a SteadyLattice, with any policy (bridge: whole hubs joined to the wall
by bridges). TurnsU and TurnsV add whole turns to U and V (the corners alone turn less than half a turn): rings and
spirals of any length, closed seamlessly when a group falls on the first (kernel/curved_ring.py)."""
import FreeCAD

from latticewb.kernel import curved_lattice, lattice_shape
from latticewb.objects import density, property_checks
from latticewb.utils import types
from latticewb.utils.proxies import StatelessProxy, add_missing_properties

_PROPERTIES = [
    ("App::PropertyVector", "A", "Corners", "Corner M(0,0) of the field (mm), unless ALink gives it"),
    ("App::PropertyVector", "B", "Corners", "Corner M(0,1): the far end of the V side from A (mm), unless BLink"),
    ("App::PropertyVector", "C", "Corners", "Corner M(1,1), opposite A (mm), unless CLink gives it"),
    ("App::PropertyVector", "D", "Corners", "Corner M(1,0): the far end of the U side from A (mm), unless DLink"),
    ("App::PropertyLinkSub", "ALink", "Corners", "A vertex giving corner A (a sketch point, Draft point, vertex)"),
    ("App::PropertyLinkSub", "BLink", "Corners", "A vertex giving corner B"),
    ("App::PropertyLinkSub", "CLink", "Corners", "A vertex giving corner C"),
    ("App::PropertyLinkSub", "DLink", "Corners", "A vertex giving corner D"),
    ("App::PropertyLinkSub", "FaceLink", "Corners",
     "A planar, cylindrical or conical face the lattice is laid on: the corners are projected onto it, the field "
     "follows its surface (C is then implied, except on a plane) and LayerOffset goes into the body"),
    ("App::PropertyInteger", "TurnsU", "Corners",
     "Whole turns added to the U side (A toward D) about the field's axis: 1 goes on one more turn the way it "
     "turns (a quarter turn becomes one and a quarter), -1 goes the other way round (three quarters). When a "
     "group falls exactly on the first, the ring is closed: the repeats are left out and the seam is joined"),
    ("App::PropertyInteger", "TurnsV", "Corners",
     "Whole turns added to the V side (A toward B) about the field's axis, as TurnsU does for U"),
    ("App::PropertyEnumeration", "Connectivity", "Lattice",
     "Beams of each group: triangle (6 per inner hub), kagome (4), honeycomb (3)"),
    ("App::PropertyIntegerConstraint", "CellsU", "Lattice", "Groups along U (from A toward D)"),
    ("App::PropertyIntegerConstraint", "CellsV", "Lattice", "Groups along V (from A toward B)"),
    ("App::PropertyIntegerConstraint", "Layers", "Lattice", "Layers of the stack (1: a slab)"),
    ("App::PropertyDistance", "LayerRaise", "Lattice",
     "How far each layer is raised along the field's axis from the one before (mm; may be negative)"),
    ("App::PropertyDistance", "LayerOffset", "Lattice",
     "How far each layer is offset along the sheet's normal at corner A from the one before (mm; may be negative; "
     "adds to LayerRaise); each layer's groups follow the field from its corner"),
    ("App::PropertyBool", "JoinLayers", "Lattice", "Join each node to its copy in the next layer by a beam"),
    ("App::PropertyLength", "NodeRadius", "Lattice",
     "Radius of the balls at corner A's node (the others are scaled with the field)"),
    ("App::PropertyFloat", "BeamRatio", "Lattice",
     "Beam radius over its nodes' radius, in (0, 1]; 0 makes each beam the convex hull of its two balls"),
    ("App::PropertyEnumeration", "Representation", "Display",
     "Preview: beam axes; Elements: balls and beams as separate solids; Auto: Elements up to %d elements"
     % lattice_shape.MAX_SOLID_ELEMENTS),
    ("App::PropertyIntegerConstraint", "PreviewBudget", "Display",
     "Most beams the preview draws; beyond it an evenly spread subset is drawn"),
    ("App::PropertyInteger", "BallCount", "Result", "Number of balls (read only)"),
    ("App::PropertyInteger", "BeamCount", "Result", "Number of beams (read only)"),
]

REPRESENTATIONS = ["Auto", "Preview", "Elements"]
MAX_COUNT = 100000  # groups along U or V: 10^10 hubs is beyond any memory


class CurvedLattice(StatelessProxy):
    Type = types.CURVED_LATTICE

    def __init__(self, obj):
        obj.Proxy = self
        self.ensure_properties(obj)

    @staticmethod
    def ensure_properties(obj):
        names = add_missing_properties(obj, _PROPERTIES)

        def default(name, value):
            if name in names:
                setattr(obj, name, value)

        for corner, point in zip(curved_lattice.CORNERS, curved_lattice.default_corners()):
            default(corner, point)
        if "Connectivity" in names:
            obj.Connectivity = curved_lattice.CONNECTIVITIES
            obj.Connectivity = "triangle"
        default("CellsU", (8, 1, MAX_COUNT, 1))
        default("CellsV", (6, 1, MAX_COUNT, 1))
        default("Layers", (1, 1, MAX_COUNT, 1))
        default("TurnsU", 0)
        default("TurnsV", 0)
        default("LayerRaise", 0.0)
        default("LayerOffset", 0.0)
        default("JoinLayers", True)
        default("NodeRadius", 1.0)
        default("BeamRatio", 0.5)
        if "Representation" in names:
            obj.Representation = REPRESENTATIONS
            obj.Representation = "Auto"
        default("PreviewBudget", (2000000, 1000, 100000000, 100000))
        for name in ("BallCount", "BeamCount"):
            obj.setEditorMode(name, 1)  # read only
        density.add_density_property(obj)
        property_checks.remember_good(obj)

    def onDocumentRestored(self, obj):
        self.ensure_properties(obj)

    def onChanged(self, obj, prop):
        if hasattr(obj, "Density"):  # the last property: not while ensure_properties adds them
            property_checks.check_lattice_property(obj, prop)

    def execute(self, obj):
        try:
            property_checks.require_sensible(obj)
            lattice, ring = curved_lattice.lattice_and_ring(obj)
        except ValueError as error:
            FreeCAD.Console.PrintError("%s: %s\n" % (obj.Label, error))
            raise ValueError("%s: %s" % (obj.Label, error)) from None
        if ring is not None:
            direction, kept, asked = ring
            FreeCAD.Console.PrintMessage(
                "%s: a closed ring of %d groups along %s: group %d falls on group 0, so the last %d of the %d asked "
                "for repeat the first ones and are left out, and the seam is joined\n"
                % (obj.Label, kept, "UV"[direction], kept, asked - kept, asked))
        self.lattice = lattice  # for the view provider's preview (not saved: rebuilt on recompute)
        property_checks.remember_good(obj)
        obj.BallCount = lattice.ball_count
        obj.BeamCount = lattice.beam_count
        elements = lattice.ball_count + lattice.beam_count
        if obj.Representation == "Elements" or (obj.Representation == "Auto"
                                                 and elements <= lattice_shape.MAX_SOLID_ELEMENTS):
            import steadylattice
            from latticewb.utils import progress
            try:
                with progress.LongOperation("Building %s as solids" % obj.Label) as report:
                    obj.Shape = lattice_shape.lattice_shape(lattice, report)
            except steadylattice.Cancelled:
                progress.keep_previous_shape(obj, "building")
        else:
            obj.Shape = lattice_shape.empty_shape()

    def preview_data(self, obj):
        """(lattice, ball mask, beam mask) for the view provider's preview (rebuilt after opening a document)."""
        lattice = getattr(self, "lattice", None)
        if lattice is None:
            try:
                lattice = self.lattice = curved_lattice.lattice(obj)
            except ValueError:
                return None
        return lattice, None, None
