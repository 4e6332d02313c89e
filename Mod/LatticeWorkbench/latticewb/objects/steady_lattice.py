"""SteadyLattice: the parametric lattice feature (Part::FeaturePython), usable without the GUI.

Its parameters sit in the property editor, grouped:
  Lattice   preset unit cell (or a custom template), cell size, cells along U V W, node and beam radii, layout
  Grading   (layout "grading") taper % per cell, twist and bend in degrees per cell, along each of U V W
  Steps     (layout "steps") the step between neighbouring cells as a placement plus a scale (or cumulative)
  Frames    (layout "frames") where the last cell along U, V and W goes, as placements plus scales
  Template  custom nodes, radii and beam patterns
  Display   Representation (Auto, Preview, Elements, Solid) and the preview budget
The object's own Placement places the whole lattice (the papers' base frame G).
"""
import FreeCAD

from latticewb.kernel import lattice_shape, presets
from latticewb.kernel.steady_lattice import CUSTOM, LAYOUTS, ORDERS, STEP_MODES, applied_order, build_lattice
from latticewb.objects import density, property_checks
from latticewb.utils import types
from latticewb.utils.proxies import StatelessProxy, add_missing_properties

REPRESENTATIONS = ["Auto", "Preview", "Elements", "Solid"]

# (type, name, group, tooltip)
_PROPERTIES = [
    ("App::PropertyEnumeration", "Preset", "Lattice",
     "Unit cell: a preset or 'custom' (Template group); switching to custom starts from the current preset"),
    ("App::PropertyLength", "CellSize", "Lattice", "Edge length of the unit cell (honeycomb: the hexagon's edge)"),
    ("App::PropertyIntegerConstraint", "CellsU", "Lattice",
     "Number of cells along U (a custom template: number of node groups along U)"),
    ("App::PropertyIntegerConstraint", "CellsV", "Lattice",
     "Number of cells along V (a custom template: number of node groups along V)"),
    ("App::PropertyIntegerConstraint", "CellsW", "Lattice",
     "Number of cells along W (a custom template: number of node groups along W)"),
    ("App::PropertyLength", "NodeRadius", "Lattice", "Radius of the balls at the nodes (presets)"),
    ("App::PropertyLength", "BeamRadius", "Lattice",
     "Radius of the beams where they meet the nodes (presets), at most NodeRadius; "
     "0 makes each beam the convex hull of its two balls"),
    ("App::PropertyEnumeration", "Layout", "Lattice",
     "How cells follow each other: grading (taper, twist, bend per cell), steps (a placement per step) "
     "or frames (placements of the last cells)"),
    ("App::PropertyEnumeration", "Order", "Lattice",
     "Order in which the steps apply, first to last. The last direction bends, twists and tapers the whole "
     "lattice about one centre line; earlier ones act row by row. Auto: graded directions last"),
    ("App::PropertyFloat", "TaperU", "Grading", "Growth per cell along U, in % (-3: each cell 3 % smaller)"),
    ("App::PropertyFloat", "TaperV", "Grading", "Growth per cell along V, in %"),
    ("App::PropertyFloat", "TaperW", "Grading", "Growth per cell along W, in %"),
    ("App::PropertyAngle", "TwistU", "Grading", "Rotation per cell about the lattice's centre line along U"),
    ("App::PropertyAngle", "TwistV", "Grading", "Rotation per cell about the lattice's centre line along V"),
    ("App::PropertyAngle", "TwistW", "Grading", "Rotation per cell about the lattice's centre line along W"),
    ("App::PropertyAngle", "BendU", "Grading", "Bend per cell of the rows along U (toward BendUToward)"),
    ("App::PropertyAngle", "BendV", "Grading", "Bend per cell of the rows along V (toward BendVToward)"),
    ("App::PropertyAngle", "BendW", "Grading", "Bend per cell of the rows along W (toward BendWToward)"),
    ("App::PropertyEnumeration", "BendUToward", "Grading", "Axis the rows along U bend toward"),
    ("App::PropertyEnumeration", "BendVToward", "Grading", "Axis the rows along V bend toward"),
    ("App::PropertyEnumeration", "BendWToward", "Grading", "Axis the rows along W bend toward"),
    ("App::PropertyEnumeration", "StepMode", "Steps",
     "incremental: U, V, W are the steps between neighbouring cells; cumulative: from the first cell to the last"),
    ("App::PropertyPlacement", "StepU", "Steps", "Step along U: rotation and translation (translation in cell units)"),
    ("App::PropertyFloatConstraint", "ScaleU", "Steps", "Scale of the step along U (1: no taper)"),
    ("App::PropertyPlacement", "StepV", "Steps", "Step along V: rotation and translation (translation in cell units)"),
    ("App::PropertyFloatConstraint", "ScaleV", "Steps", "Scale of the step along V (1: no taper)"),
    ("App::PropertyPlacement", "StepW", "Steps", "Step along W: rotation and translation (translation in cell units)"),
    ("App::PropertyFloatConstraint", "ScaleW", "Steps", "Scale of the step along W (1: no taper)"),
    ("App::PropertyPlacement", "EndU", "Frames",
     "Where the last cell along U goes, relative to the lattice's Placement (the first cell sits at its origin)"),
    ("App::PropertyFloatConstraint", "EndScaleU", "Frames", "Size of the last cell along U relative to the first"),
    ("App::PropertyPlacement", "EndV", "Frames", "Where the last cell along V goes, relative to the lattice's Placement"),
    ("App::PropertyFloatConstraint", "EndScaleV", "Frames", "Size of the last cell along V relative to the first"),
    ("App::PropertyPlacement", "EndW", "Frames", "Where the last cell along W goes, relative to the lattice's Placement"),
    ("App::PropertyFloatConstraint", "EndScaleW", "Frames", "Size of the last cell along W relative to the first"),
    ("App::PropertyVectorList", "Nodes", "Template", "Custom template: node centres in cell units"),
    ("App::PropertyFloatList", "NodeRadii", "Template", "Custom template: node radii (mm), one per node"),
    ("App::PropertyStringList", "Beams", "Template",
     "Custom template: beam patterns 'n1 di dj dk n2' joining node n1 of cell (i,j,k) to node n2 of cell "
     "(i+di, j+dj, k+dk); append 'r1 r2' (mm) for beams thinner than their nodes"),
    ("App::PropertyEnumeration", "Representation", "Display",
     "Preview: beam axes (fast at 10^6 beams); Elements: balls and beams as separate solids; Solid: the lattice as "
     "one exact B-rep solid (their union); Auto: Elements up to %d elements, Preview beyond"
     % lattice_shape.MAX_SOLID_ELEMENTS),
    ("App::PropertyIntegerConstraint", "PreviewBudget", "Display",
     "Most beams the preview draws; beyond it an evenly spread subset is drawn"),
    ("App::PropertyString", "AppliedOrder", "Result",
     "The order the steps apply in, first to last (read only; Auto resolved)"),
    ("App::PropertyInteger", "BallCount", "Result", "Number of balls (read only)"),
    ("App::PropertyInteger", "BeamCount", "Result", "Number of beams (read only)"),
]

_MAX_CELLS = 1000000
_SCALE_RANGE = (1e-3, 1e3)  # a scale of more than 1000x per cell is a typo, not a design


class SteadyLattice(StatelessProxy):
    """Proxy of a SteadyLattice document object."""

    Type = types.STEADY_LATTICE

    def __init__(self, obj):
        obj.Proxy = self
        self.ensure_properties(obj)

    @staticmethod
    def ensure_properties(obj):
        """Adds missing properties with their defaults (new objects, and documents from older versions)."""
        names = add_missing_properties(obj, _PROPERTIES)

        def default(name, value):
            if name in names:
                setattr(obj, name, value)

        if "Preset" in names:
            obj.Preset = presets.PRESET_NAMES + [CUSTOM]
            obj.Preset = "octet"
        default("CellSize", 10.0)
        default("NodeRadius", 1.2)
        default("BeamRadius", 0.8)
        if "Layout" in names:
            obj.Layout = LAYOUTS
            obj.Layout = "grading"
        if "Order" in names:
            obj.Order = ORDERS
            obj.Order = "Auto"
        if "StepMode" in names:
            obj.StepMode = STEP_MODES
            obj.StepMode = "incremental"
        for axis in "UVW":
            default("Cells" + axis, (3, 1, _MAX_CELLS, 1))
            default("Scale" + axis, (1.0, _SCALE_RANGE[0], _SCALE_RANGE[1], 0.01))
            default("EndScale" + axis, (1.0, _SCALE_RANGE[0], _SCALE_RANGE[1], 0.01))
            unit = FreeCAD.Vector(*(1.0 if a == axis else 0.0 for a in "UVW"))
            default("Step" + axis, FreeCAD.Placement(unit, FreeCAD.Rotation()))
            default("End" + axis, FreeCAD.Placement(unit * 30.0, FreeCAD.Rotation()))
            toward = "Bend%sToward" % axis
            if toward in names:
                others = [a for a in "UVW" if a != axis]
                setattr(obj, toward, others)
                setattr(obj, toward, others[0])
        if "Representation" in names:
            obj.Representation = REPRESENTATIONS
            obj.Representation = "Auto"
        default("PreviewBudget", (2000000, 1000, 100000000, 100000))
        for name in ("AppliedOrder", "BallCount", "BeamCount"):
            obj.setEditorMode(name, 1)  # read only
        density.add_density_property(obj)
        update_visible_groups(obj)
        property_checks.remember_good(obj)

    def onDocumentRestored(self, obj):
        self.ensure_properties(obj)

    def onChanged(self, obj, prop):
        if not hasattr(obj, "Representation"):
            return  # still adding properties
        property_checks.check_lattice_property(obj, prop)
        if prop == "Preset" and obj.Preset == CUSTOM and not obj.Nodes:
            start_custom_template(obj)
        if prop == "Layout":
            update_visible_groups(obj)
            carry_over_layout(obj, getattr(self, "lattice", None))

    def execute(self, obj):
        try:
            property_checks.require_sensible(obj)  # names the property, where the kernel would name its own fields
            lattice = build_lattice(obj)
        except ValueError as error:
            FreeCAD.Console.PrintError("%s: %s\n" % (obj.Label, error))
            raise ValueError("%s: %s" % (obj.Label, error)) from None
        self.lattice = lattice  # kept for the view provider's preview (not saved: rebuilt on recompute)
        property_checks.remember_good(obj)
        obj.AppliedOrder = applied_order(obj)
        obj.BallCount = lattice.ball_count
        obj.BeamCount = lattice.beam_count
        if obj.Representation == "Solid" or shows_solids(obj):
            import steadylattice
            from latticewb.utils import progress
            exact = obj.Representation == "Solid"
            try:
                with progress.LongOperation("Building %s as %s" % (obj.Label, "one solid" if exact else "solids")) \
                        as report:
                    obj.Shape = (lattice_shape.exact_solid(lattice, report) if exact
                                 else lattice_shape.lattice_shape(lattice, report))
            except steadylattice.Cancelled:
                # not an error: the previous shape stays, the object shows as needing recompute
                progress.keep_previous_shape(obj, "building")
        else:
            obj.Shape = lattice_shape.empty_shape()

    def preview_data(self, obj):
        """(lattice, ball mask, beam mask) for the view provider's preview; the kernel lattice is not saved with the
        document, so after opening it is rebuilt here."""
        lattice = getattr(self, "lattice", None)
        if lattice is None:
            try:
                lattice = self.lattice = build_lattice(obj)
            except ValueError:
                return None
        return lattice, None, None


def shows_solids(obj):
    """Whether the lattice is shown as separate element solids (Elements, or Auto for small lattices)."""
    if obj.Representation == "Elements":
        return True
    return obj.Representation == "Auto" and obj.BallCount + obj.BeamCount <= lattice_shape.MAX_SOLID_ELEMENTS


def update_visible_groups(obj):
    """Shows the property group of the chosen layout and hides the others (mode 2 = hidden)."""
    layout = getattr(obj, "Layout", "grading")
    groups = {"grading": ["Taper", "Twist", "Bend"], "steps": ["StepMode", "Step", "Scale"], "frames": ["End"]}
    for mode, prefixes in groups.items():
        for name in obj.PropertiesList:
            if any(name.startswith(p) for p in prefixes) and obj.getGroupOfProperty(name) in ("Grading", "Steps", "Frames"):
                obj.setEditorMode(name, 0 if mode == layout else 2)


def carry_over_layout(obj, lattice):
    """When the layout changes, the new layout's parameters start from the lattice as it was built, so the
    lattice does not jump: steps take the lattice's U, V, W; frames take the placements of its last cells."""
    if lattice is None or not obj.AppliedOrder:
        return
    obj.Order = obj.AppliedOrder  # keep the order the lattice was built with
    steps = (lattice.U, lattice.V, lattice.W)
    counts = lattice.counts
    for a, axis in enumerate("UVW"):
        if obj.Layout == "steps":
            obj.StepMode = "incremental"
            setattr(obj, "Step" + axis, _similarity_placement(steps[a], 1.0 / obj.CellSize.Value))
            setattr(obj, "Scale" + axis, steps[a].scale)
        elif obj.Layout == "frames":
            index = [0, 0, 0]
            index[a] = counts[a] - 1
            end = lattice.group(*index)
            setattr(obj, "End" + axis, _similarity_placement(end, 1.0))
            setattr(obj, "EndScale" + axis, end.scale)


def _similarity_placement(similarity, translation_unit):
    """The placement (rotation, translation / unit) of p -> s R p + t; the scale is returned separately."""
    m = similarity.rotation_matrix
    matrix = FreeCAD.Matrix(m[0][0], m[0][1], m[0][2], 0, m[1][0], m[1][1], m[1][2], 0, m[2][0], m[2][1], m[2][2], 0)
    t = similarity.translation_part * translation_unit
    return FreeCAD.Placement(FreeCAD.Vector(*t), FreeCAD.Rotation(matrix))


def start_custom_template(obj):
    """Fills the custom template from the octet preset, so switching to 'custom' starts from something editable."""
    basis, _, patterns = presets.preset_template("octet")
    obj.Nodes = [FreeCAD.Vector(*b) for b in basis]
    obj.NodeRadii = [obj.NodeRadius.Value] * len(basis)
    obj.Beams = [" ".join(str(x) for x in p) for p in patterns]
