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

from latticewb import presets
from latticewb.features import grading, lattice_shape, mass_properties, property_checks
from latticewb.proxies import StatelessProxy, add_missing_properties

CUSTOM = "custom"
LAYOUTS = ["grading", "steps", "frames"]
ORDERS = ["Auto", "UVW", "UWV", "VUW", "VWU", "WUV", "WVU"]
STEP_MODES = ["incremental", "cumulative"]
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
     "The order the steps apply in (read only); the kernel lattice's indices (i, j, k) follow it"),
    ("App::PropertyInteger", "BallCount", "Result", "Number of balls (read only)"),
    ("App::PropertyInteger", "BeamCount", "Result", "Number of beams (read only)"),
]

_MAX_CELLS = 1000000
_SCALE_RANGE = (1e-3, 1e3)  # a scale of more than 1000x per cell is a typo, not a design


class SteadyLattice(StatelessProxy):
    """Proxy of a SteadyLattice document object."""

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
        mass_properties.add_density_property(obj)
        update_visible_groups(obj)

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
            lattice = build_lattice(obj)
        except ValueError as error:
            FreeCAD.Console.PrintError("%s: %s\n" % (obj.Label, error))
            raise ValueError("%s: %s" % (obj.Label, error)) from None
        self.lattice = lattice  # kept for the view provider's preview (not saved: rebuilt on recompute)
        obj.AppliedOrder = "".join("UVW"[a] for a in applied_order(obj))
        obj.BallCount = lattice.ball_count
        obj.BeamCount = lattice.beam_count
        if obj.Representation == "Solid" or shows_solids(obj):
            import steadylattice
            from latticewb import progress
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
    order = [("UVW").index(a) for a in obj.AppliedOrder]
    obj.Order = obj.AppliedOrder  # keep the order the lattice was built with
    slot_steps = (lattice.U, lattice.V, lattice.W)
    counts = lattice.counts
    for slot, a in enumerate(order):
        axis = "UVW"[a]
        if obj.Layout == "steps":
            obj.StepMode = "incremental"
            setattr(obj, "Step" + axis, _similarity_placement(slot_steps[slot], 1.0 / obj.CellSize.Value))
            setattr(obj, "Scale" + axis, slot_steps[slot].scale)
        elif obj.Layout == "frames":
            index = [0, 0, 0]
            index[slot] = counts[slot] - 1
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


def parse_beam(text, index):
    """A beam pattern from 'n1 di dj dk n2' or 'n1 di dj dk n2 r1 r2'."""
    fields = text.split()
    where = "Beams[%d]" % index
    if len(fields) not in (5, 7):
        raise ValueError("%s: expected 'n1 di dj dk n2' or 'n1 di dj dk n2 r1 r2' (got %r)" % (where, text))
    try:
        ints = [int(f) for f in fields[:5]]
        radii = [float(f) for f in fields[5:]]
    except ValueError:
        raise ValueError("%s: expected integers n1 di dj dk n2 and numbers r1 r2 (got %r)" % (where, text)) from None
    return tuple(ints + radii)


def cell_aspect(obj):
    if obj.Preset == CUSTOM:
        return (1.0, 1.0, 1.0)
    return presets.PRESETS[obj.Preset][1]


def template(obj):
    """(nodes [((x, y, z), r)] in mm, beam patterns, omitted nodes, group counts) of the feature's unit cell."""
    cell = obj.CellSize.Value
    if not cell > 0.0:
        raise ValueError("CellSize: must be > 0 (got %g)" % cell)
    cells = (obj.CellsU, obj.CellsV, obj.CellsW)
    if obj.Preset == CUSTOM:
        if len(obj.NodeRadii) != len(obj.Nodes):
            raise ValueError("NodeRadii: give one radius per node (%d nodes, %d radii)"
                             % (len(obj.Nodes), len(obj.NodeRadii)))
        nodes = [((v.x * cell, v.y * cell, v.z * cell), r) for v, r in zip(obj.Nodes, obj.NodeRadii)]
        beams = [parse_beam(text, q) for q, text in enumerate(obj.Beams)]
        return nodes, beams, [], cells
    basis, aspect, patterns = presets.preset_template(obj.Preset)
    node_radius, beam_radius = obj.NodeRadius.Value, obj.BeamRadius.Value
    if not node_radius > 0.0:
        raise ValueError("NodeRadius: must be > 0 (got %g)" % node_radius)
    if beam_radius > node_radius:
        raise ValueError("BeamRadius: must not exceed NodeRadius (%g > %g)" % (beam_radius, node_radius))
    nodes = [(tuple(b[a] * aspect[a] * cell for a in range(3)), node_radius) for b in basis]
    if 0.0 < beam_radius < node_radius:
        patterns = [p + (beam_radius, beam_radius) for p in patterns]
    # one group per cell corner; the nodes of the far layers that stick out of the box of cells are omitted
    counts = tuple(c + 1 for c in cells)
    return nodes, patterns, presets.outside_nodes(basis, cells), counts


def _placement_similarity(placement, scale, translation_unit):
    """p -> R (scale p) + translation_unit * base, from a FreeCAD placement."""
    import steadylattice as sl

    rotation = placement.Rotation
    base = placement.Base
    step = sl.Similarity.translation((base.x * translation_unit, base.y * translation_unit, base.z * translation_unit))
    if rotation.Angle != 0.0:
        axis = rotation.Axis
        step = step * sl.Similarity.rotation(rotation.Angle, (axis.x, axis.y, axis.z))
    return step * sl.Similarity.dilation(scale)


def _grading_steps(obj, counts):
    cell = obj.CellSize.Value
    aspect = cell_aspect(obj)
    edges = [cell * aspect[a] for a in range(3)]
    # the lattice's centre lines: the middle of the box of groups
    middle = [edges[a] * (counts[a] - 1) / 2.0 for a in range(3)]
    steps = []
    for a, axis in enumerate("UVW"):
        cell_vector = tuple(edges[a] if b == a else 0.0 for b in range(3))
        centre = tuple(0.0 if b == a else middle[b] for b in range(3))
        steps.append(grading.grading_step(axis, cell_vector, centre,
                                          taper_percent=getattr(obj, "Taper" + axis),
                                          twist_degrees=getattr(obj, "Twist" + axis).Value,
                                          bend_degrees=getattr(obj, "Bend" + axis).Value,
                                          bend_toward=getattr(obj, "Bend%sToward" % axis)))
    return steps


def _rotates_or_scales(obj, axis):
    return (getattr(obj, "Taper" + axis) != 0.0 or getattr(obj, "Twist" + axis).Value != 0.0
            or getattr(obj, "Bend" + axis).Value != 0.0)


def applied_order(obj):
    """The physical directions (0, 1, 2 for U, V, W) in the order their steps apply, first to last."""
    if obj.Order != "Auto":
        return tuple("UVW".index(a) for a in obj.Order)
    if obj.Layout != "grading":
        return (0, 1, 2)
    # graded directions last (stable): the last one grades the whole lattice about one centre line
    return tuple(sorted(range(3), key=lambda a: (_rotates_or_scales(obj, "UVW"[a]), a)))


def _in_order(order, values):
    return tuple(values[a] for a in order)


def build_lattice(obj):
    """The steadylattice.Lattice of a SteadyLattice object (in its local coordinates; obj.Placement places it).
    Its group indices (i, j, k) follow obj.AppliedOrder (the order the steps apply in)."""
    import steadylattice as sl

    nodes, beams, omitted, counts = template(obj)
    order = applied_order(obj)
    beams = [(b[0],) + _in_order(order, b[1:4]) + tuple(b[4:]) for b in beams]
    omitted = [_in_order(order, o[:3]) + (o[3],) for o in omitted]
    kernel_counts = _in_order(order, counts)
    if obj.Layout == "grading":
        steps = _in_order(order, _grading_steps(obj, counts))
        return sl.Lattice(nodes, beams, kernel_counts, *steps, omitted=omitted)
    if obj.Layout == "steps":
        steps = _in_order(order, [_placement_similarity(getattr(obj, "Step" + a), getattr(obj, "Scale" + a),
                                                        obj.CellSize.Value) for a in "UVW"])
        if obj.StepMode == "cumulative":
            return sl.Lattice.interpolating(nodes, beams, kernel_counts, *steps, omitted=omitted)
        return sl.Lattice(nodes, beams, kernel_counts, *steps, omitted=omitted)
    # frames: the cumulative similarity of each direction takes the first cell (at the origin) to its end placement
    totals = _in_order(order, [_placement_similarity(getattr(obj, "End" + a), getattr(obj, "EndScale" + a), 1.0)
                               for a in "UVW"])
    return sl.Lattice.interpolating(nodes, beams, kernel_counts, *totals, omitted=omitted)


def make_steady_lattice(doc, name="SteadyLattice"):
    """Adds a SteadyLattice to `doc` (with a view provider when the GUI is up) and returns it."""
    obj = doc.addObject("Part::FeaturePython", name)
    SteadyLattice(obj)
    if FreeCAD.GuiUp:
        from latticewb.gui import view_providers
        view_providers.ViewProviderSteadyLattice(obj.ViewObject)
    return obj
