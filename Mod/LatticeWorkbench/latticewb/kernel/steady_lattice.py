"""A SteadyLattice object's kernel lattice: its template (preset or custom), its layout (grading, steps or frames,
in the order the steps apply) and its placement, read from the object's properties."""
from latticewb.kernel import grading, presets

CUSTOM = "custom"
LAYOUTS = ["grading", "steps", "frames"]
ORDERS = ["Auto", "UVW", "UWV", "VUW", "VWU", "WUV", "WVU"]
STEP_MODES = ["incremental", "cumulative"]


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
    return nodes, patterns, presets.outside_nodes(obj.Preset, cells), counts


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
    """The order the steps apply in, first to last, as letters ("UVW", "VWU", ...). Auto: with the grading
    layout the graded directions last (stable), so that the last one grades the whole lattice about one centre
    line; otherwise U V W."""
    if obj.Order != "Auto":
        return obj.Order
    if obj.Layout != "grading":
        return "UVW"
    return "".join(sorted("UVW", key=lambda a: (_rotates_or_scales(obj, a), "UVW".index(a))))


def build_lattice(obj):
    """The steadylattice.Lattice of a SteadyLattice object, in its local coordinates (obj.Placement places it).
    Its group indices (i, j, k) count cells along U, V, W whatever the order the steps apply in."""
    import steadylattice as sl

    nodes, beams, omitted, counts = template(obj)
    order = applied_order(obj)
    if obj.Layout == "grading":
        return sl.Lattice(nodes, beams, counts, *_grading_steps(obj, counts), omitted=omitted, order=order)
    if obj.Layout == "steps":
        steps = [_placement_similarity(getattr(obj, "Step" + a), getattr(obj, "Scale" + a), obj.CellSize.Value)
                 for a in "UVW"]
        make = sl.Lattice.interpolating if obj.StepMode == "cumulative" else sl.Lattice
        return make(nodes, beams, counts, *steps, omitted=omitted, order=order)
    # frames: the cumulative similarity of each direction takes the first cell (at the origin) to its end placement
    totals = [_placement_similarity(getattr(obj, "End" + a), getattr(obj, "EndScale" + a), 1.0) for a in "UVW"]
    return sl.Lattice.interpolating(nodes, beams, counts, *totals, omitted=omitted, order=order)


def placement_similarity(placement):
    """The similarity of a FreeCAD placement (rotation, then translation)."""
    return _placement_similarity(placement, 1.0, 1.0)


def lattice(obj):
    """The steadylattice.Lattice of a SteadyLattice object, placed by the object's Placement."""
    return build_lattice(obj).placed(placement_similarity(obj.Placement))
