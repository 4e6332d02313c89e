"""SteadyLattice: the parametric lattice feature (Part::FeaturePython), usable without the GUI.

Its parameters sit in the property editor: a preset unit cell (or a custom template), the cell size, the
counts of cells, the ball and beam radii, and the steps U, V, W between neighbouring cells, each a placement
plus a scale in cell units (incremental: the step from one cell to the next; cumulative: from the first cell
to the last, the step being its 1/(count-1) power). The object's own Placement places the whole lattice (G).
"""
import FreeCAD

from latticewb import presets
from latticewb.features import lattice_shape

CUSTOM = "custom"
STEP_MODES = ["incremental", "cumulative"]

# (type, name, group, tooltip)
_PROPERTIES = [
    ("App::PropertyEnumeration", "Preset", "Lattice",
     "Unit cell: a preset (cubic, BCC, FCC, octet) or 'custom' (Nodes, NodeRadii and Beams below)"),
    ("App::PropertyLength", "CellSize", "Lattice", "Edge length of the unit cell"),
    ("App::PropertyIntegerConstraint", "CellsU", "Lattice",
     "Number of cells along U (a custom template: number of node groups along U)"),
    ("App::PropertyIntegerConstraint", "CellsV", "Lattice",
     "Number of cells along V (a custom template: number of node groups along V)"),
    ("App::PropertyIntegerConstraint", "CellsW", "Lattice",
     "Number of cells along W (a custom template: number of node groups along W)"),
    ("App::PropertyLength", "NodeRadius", "Lattice", "Radius of the balls at the nodes (presets)"),
    ("App::PropertyLength", "BeamRadius", "Lattice",
     "Radius of the beams where they meet the nodes (presets); 0 makes each beam the convex hull of its two balls"),
    ("App::PropertyVectorList", "Nodes", "Template", "Custom template: node centres in cell units"),
    ("App::PropertyFloatList", "NodeRadii", "Template", "Custom template: node radii (mm), one per node"),
    ("App::PropertyStringList", "Beams", "Template",
     "Custom template: beam patterns 'n1 di dj dk n2' joining node n1 of cell (i,j,k) to node n2 of cell "
     "(i+di, j+dj, k+dk); append 'r1 r2' (mm) for beams thinner than their nodes"),
    ("App::PropertyEnumeration", "StepMode", "Steps",
     "incremental: U, V, W are the steps between neighbouring cells; cumulative: from the first cell to the last"),
    ("App::PropertyPlacement", "StepU", "Steps", "Step along U: rotation and translation (translation in cell units)"),
    ("App::PropertyFloatConstraint", "ScaleU", "Steps", "Scale of the step along U (1: no taper)"),
    ("App::PropertyPlacement", "StepV", "Steps", "Step along V: rotation and translation (translation in cell units)"),
    ("App::PropertyFloatConstraint", "ScaleV", "Steps", "Scale of the step along V (1: no taper)"),
    ("App::PropertyPlacement", "StepW", "Steps", "Step along W: rotation and translation (translation in cell units)"),
    ("App::PropertyFloatConstraint", "ScaleW", "Steps", "Scale of the step along W (1: no taper)"),
    ("App::PropertyInteger", "BallCount", "Result", "Number of balls (read only)"),
    ("App::PropertyInteger", "BeamCount", "Result", "Number of beams (read only)"),
]

_MAX_CELLS = 1000000
_SCALE_RANGE = (1e-3, 1e3)  # a step scaling by more than 1000x per cell is a typo, not a design


class SteadyLattice:
    """Proxy of a SteadyLattice document object."""

    def __init__(self, obj):
        obj.Proxy = self
        self.ensure_properties(obj)

    @staticmethod
    def ensure_properties(obj):
        """Adds missing properties with their defaults (new objects, and documents from older versions)."""
        fresh = [p for p in _PROPERTIES if p[1] not in obj.PropertiesList]
        for kind, name, group, tip in fresh:
            obj.addProperty(kind, name, group, tip)
        names = {p[1] for p in fresh}
        if "Preset" in names:
            obj.Preset = presets.PRESET_NAMES + [CUSTOM]
            obj.Preset = "octet"
        if "CellSize" in names:
            obj.CellSize = 10.0
        for axis in "UVW":
            if "Cells" + axis in names:
                setattr(obj, "Cells" + axis, (3, 1, _MAX_CELLS, 1))
            if "Scale" + axis in names:
                setattr(obj, "Scale" + axis, (1.0, _SCALE_RANGE[0], _SCALE_RANGE[1], 0.01))
            if "Step" + axis in names:
                unit = FreeCAD.Vector(*(1.0 if a == axis else 0.0 for a in "UVW"))
                setattr(obj, "Step" + axis, FreeCAD.Placement(unit, FreeCAD.Rotation()))
        if "NodeRadius" in names:
            obj.NodeRadius = 1.2
        if "BeamRadius" in names:
            obj.BeamRadius = 0.8
        if "StepMode" in names:
            obj.StepMode = STEP_MODES
            obj.StepMode = "incremental"
        for name in ("BallCount", "BeamCount"):
            obj.setEditorMode(name, 1)  # read only

    def onDocumentRestored(self, obj):
        self.ensure_properties(obj)

    def onChanged(self, obj, prop):
        # Switching a preset to 'custom' starts the custom template from the preset, so it can be edited.
        if prop == "Preset" and getattr(obj, "Preset", None) == CUSTOM and not obj.Nodes:
            basis, patterns = presets.preset_template("octet")
            obj.Nodes = [FreeCAD.Vector(*b) for b in basis]
            obj.NodeRadii = [obj.NodeRadius.Value] * len(basis)
            obj.Beams = [" ".join(str(x) for x in p) for p in patterns]

    def execute(self, obj):
        try:
            lattice = build_lattice(obj)
        except ValueError as error:
            FreeCAD.Console.PrintError("%s: %s\n" % (obj.Label, error))
            raise
        obj.BallCount = lattice.ball_count
        obj.BeamCount = lattice.beam_count
        obj.Shape = lattice_shape.lattice_shape(lattice)

    def dumps(self):
        return None  # everything lives in the properties

    def loads(self, state):
        return None

    # FreeCAD <= 0.21 calls these instead of dumps/loads
    __getstate__ = dumps
    __setstate__ = loads


def step_similarity(placement, scale, cell_size):
    """The step p -> R (scale p) + cell_size * base, from a placement whose translation is in cell units."""
    import steadylattice as sl

    rotation = placement.Rotation
    axis = rotation.Axis
    base = placement.Base
    step = sl.Similarity.translation((base.x * cell_size, base.y * cell_size, base.z * cell_size))
    if abs(rotation.Angle) > 0.0:
        step = step * sl.Similarity.rotation(rotation.Angle, (axis.x, axis.y, axis.z))
    return step * sl.Similarity.dilation(scale)


def _parse_beam(text, index):
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


def template(obj):
    """(nodes [((x, y, z), r)] in mm, beam patterns, omitted nodes) of the feature's unit cell."""
    cell = obj.CellSize.Value
    if not cell > 0.0:
        raise ValueError("CellSize: must be > 0 (got %g)" % cell)
    cells = (obj.CellsU, obj.CellsV, obj.CellsW)
    if obj.Preset == CUSTOM:
        if len(obj.NodeRadii) != len(obj.Nodes):
            raise ValueError("NodeRadii: give one radius per node (%d nodes, %d radii)"
                             % (len(obj.Nodes), len(obj.NodeRadii)))
        basis = [(v.x, v.y, v.z) for v in obj.Nodes]
        nodes = [((b[0] * cell, b[1] * cell, b[2] * cell), r) for b, r in zip(basis, obj.NodeRadii)]
        beams = [_parse_beam(text, q) for q, text in enumerate(obj.Beams)]
        return nodes, beams, []
    basis, patterns = presets.preset_template(obj.Preset)
    node_radius, beam_radius = obj.NodeRadius.Value, obj.BeamRadius.Value
    if not node_radius > 0.0:
        raise ValueError("NodeRadius: must be > 0 (got %g)" % node_radius)
    if beam_radius > node_radius:
        raise ValueError("BeamRadius: must not exceed NodeRadius (%g > %g)" % (beam_radius, node_radius))
    nodes = [((b[0] * cell, b[1] * cell, b[2] * cell), node_radius) for b in basis]
    if 0.0 < beam_radius < node_radius:
        patterns = [p + (beam_radius, beam_radius) for p in patterns]
    # one group per cell corner; the nodes of the far layers that stick out of the box of cells are omitted
    return nodes, patterns, presets.outside_nodes(basis, cells)


def build_lattice(obj):
    """The steadylattice.Lattice of a SteadyLattice object (in its local coordinates; obj.Placement places it)."""
    import steadylattice as sl

    nodes, beams, omitted = template(obj)
    cell = obj.CellSize.Value
    steps = [step_similarity(getattr(obj, "Step" + a), getattr(obj, "Scale" + a), cell) for a in "UVW"]
    preset = obj.Preset != CUSTOM
    counts = tuple(getattr(obj, "Cells" + a) + (1 if preset else 0) for a in "UVW")
    if obj.StepMode == "cumulative":
        return sl.Lattice.interpolating(nodes, beams, counts, *steps, omitted=omitted)
    return sl.Lattice(nodes, beams, counts, *steps, omitted=omitted)


def make_steady_lattice(doc, name="SteadyLattice"):
    """Adds a SteadyLattice to `doc` (with a view provider when the GUI is up) and returns it."""
    obj = doc.addObject("Part::FeaturePython", name)
    SteadyLattice(obj)
    if FreeCAD.GuiUp:
        from latticewb.gui import view_providers
        view_providers.ViewProviderSteadyLattice(obj.ViewObject)
    return obj
