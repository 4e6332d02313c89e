"""What a Python-console user or a macro calls.

    import FreeCAD
    from latticewb import api
    doc = FreeCAD.newDocument()
    lat = api.make_lattice(doc, preset="octet", cell_size=10, cells=(4, 4, 4), node_radius=1.2, beam_radius=0.8)
    doc.recompute()
    api.export([lat], "/tmp/octet.step")
"""
import os

import FreeCAD

from latticewb.features import steady_lattice

# keyword -> property of SteadyLattice
_LATTICE_PARAMETERS = {
    "cell_size": "CellSize", "node_radius": "NodeRadius", "beam_radius": "BeamRadius", "layout": "Layout",
    "step_mode": "StepMode", "nodes": "Nodes", "node_radii": "NodeRadii", "beams": "Beams",
    "placement": "Placement", "representation": "Representation", "preview_budget": "PreviewBudget",
}
for _axis in "UVW":
    _a = _axis.lower()
    _LATTICE_PARAMETERS.update({
        "taper_" + _a: "Taper" + _axis, "twist_" + _a: "Twist" + _axis, "bend_" + _a: "Bend" + _axis,
        "bend_%s_toward" % _a: "Bend%sToward" % _axis, "step_" + _a: "Step" + _axis, "scale_" + _a: "Scale" + _axis,
        "end_" + _a: "End" + _axis, "end_scale_" + _a: "EndScale" + _axis,
    })


def make_lattice(doc, preset=None, **params):
    """Adds a SteadyLattice to `doc` and returns it (recompute the document to build it).

    preset: "cubic", "BCC", "FCC", "octet", "diamond", "Kelvin", "honeycomb" or "custom" (default octet).
    params (all optional): cells=(u, v, w), cell_size, node_radius, beam_radius (0: beams are the hulls of
    their balls), layout ("grading", "steps" or "frames"), placement, representation ("Auto", "Preview",
    "Elements", "Solid"), preview_budget;
      grading: taper_u / _v / _w (% per cell), twist_u / _v / _w and bend_u / _v / _w (degrees per cell),
               bend_u_toward / bend_v_toward / bend_w_toward ("U", "V" or "W");
      steps:   step_mode ("incremental" or "cumulative"), step_u / _v / _w (FreeCAD.Placement, translation in
               cell units), scale_u / _v / _w;
      frames:  end_u / _v / _w (FreeCAD.Placement of the last cell along each direction), end_scale_u / _v / _w;
      custom:  nodes (vectors in cell units), node_radii (mm), beams (strings 'n1 di dj dk n2 [r1 r2]').
    Unknown parameters raise ValueError.
    """
    obj = steady_lattice.make_steady_lattice(doc)
    if preset is not None:
        known = obj.getEnumerationsOfProperty("Preset")
        if preset not in known:
            doc.removeObject(obj.Name)
            raise ValueError("preset: unknown preset %r (known: %s)" % (preset, ", ".join(known)))
        obj.Preset = preset
    try:
        for key, value in params.items():
            if key == "cells":
                obj.CellsU, obj.CellsV, obj.CellsW = (int(c) for c in value)
            elif key in _LATTICE_PARAMETERS:
                setattr(obj, _LATTICE_PARAMETERS[key], value)
            else:
                raise ValueError("%s: unknown parameter (known: cells, %s)" % (key, ", ".join(_LATTICE_PARAMETERS)))
    except Exception:
        doc.removeObject(obj.Name)
        raise
    return obj


def make_part(doc, lattice, body=None, policy="clip", skin=0.0, dangling="keep"):
    """Adds a LatticePart: `lattice` (a SteadyLattice) trimmed into `body` (an object with a solid Shape, or None
    for the whole lattice) as one exact B-rep solid. policy: "clip" (cut at the boundary) or "whole" (only hubs
    entirely inside); skin: wall thickness of the body's skin united with the lattice (0: none); dangling: "keep"
    or "remove" beams joining a kept hub to a dropped one. Recompute the document to build it."""
    from latticewb.features import lattice_part
    if policy not in lattice_part.POLICIES:
        raise ValueError("policy: expected one of %s (got %r)" % (", ".join(lattice_part.POLICIES), policy))
    if dangling not in lattice_part.DANGLING:
        raise ValueError("dangling: expected one of %s (got %r)" % (", ".join(lattice_part.DANGLING), dangling))
    if not skin >= 0.0:
        raise ValueError("skin: must be >= 0 (got %r)" % (skin,))
    if not hasattr(lattice, "Preset"):
        raise ValueError("lattice: expected a SteadyLattice object")
    return lattice_part.make_lattice_part(doc, lattice, body, policy, skin, dangling)


_FILTER_PARAMETERS = {
    "invert": "Invert", "stencil_size": "StencilSize", "stencil_mask": "StencilMask", "coarse": "Coarse",
    "gyroid_period": "GyroidPeriod", "gyroid_thickness": "GyroidThickness", "gyroid_mode": "GyroidMode",
    "body": "Body",
}


def make_filter(doc, source, kind="stencil", **params):
    """Adds a LatticeFilter of `source` (a SteadyLattice or another LatticeFilter; filters cascade).

    kind: "stencil" (stencil_size=(x, y, z), stencil_mask="10..." one character per cell of the period, i fastest),
    "lattice-in-lattice" (coarse=<SteadyLattice or LatticeFilter>), "gyroid" (gyroid_period, gyroid_thickness,
    gyroid_mode "sheet" or "solid") or "inside body" (body=<object with a solid Shape>); invert=True keeps the
    complement. Recompute the document to evaluate it."""
    from latticewb.features import lattice_filter
    if not lattice_filter.is_lattice_source(source):
        raise ValueError("source: expected a SteadyLattice or LatticeFilter")
    if kind not in lattice_filter.KINDS:
        raise ValueError("kind: expected one of %s (got %r)" % (", ".join(lattice_filter.KINDS), kind))
    unknown = set(params) - set(_FILTER_PARAMETERS)
    if unknown:
        raise ValueError("%s: unknown parameter (known: %s)" % (sorted(unknown)[0], ", ".join(_FILTER_PARAMETERS)))
    values = {_FILTER_PARAMETERS[k]: (list(v) if k == "stencil_size" else v) for k, v in params.items()}
    return lattice_filter.make_lattice_filter(doc, source, kind, **values)


def properties(obj):
    """Mass properties of a SteadyLattice (closed form from the kernel) or of a part or any solid (B-rep
    integration): a dict with volume (mm^3), area (mm^2), centroid (mm), inertia (3x3 about the centroid, kg mm^2),
    mass (kg) and density (g/cm^3, the object's Density property, 1 when it has none), and the method used.
    A lattice whose hubs overlap is reported in the report view (which hubs) and measured as the exact union of
    the overlapping hubs ("overlaps" counts the pairs)."""
    from latticewb.features import mass_properties
    return mass_properties.properties(obj)


def target_density(obj, relative_density=None, mass=None):
    """Scales every radius of a SteadyLattice so that it reaches a relative density (its volume over the volume of
    its box of cells) or a mass in kg (at its Density); returns the factor applied. Recompute to rebuild."""
    from latticewb.features import mass_properties
    if not hasattr(obj, "Preset"):
        raise ValueError("obj: expected a SteadyLattice")
    scale = mass_properties.scale_for_target(obj, relative_density=relative_density, mass=mass)
    mass_properties.apply_radius_scale(obj, scale)
    return scale


def lattice(obj):
    """The steadylattice.Lattice of a SteadyLattice object, placed by the object's Placement.
    Its group indices (i, j, k) follow the order the steps apply in, obj.AppliedOrder (for example "VWU": i counts
    cells along V, j along W, k along U); ball_index_of(obj, lattice, ...) translates from U, V, W indices."""
    import steadylattice as sl
    local = steady_lattice.build_lattice(obj)
    return sl.Lattice.from_json(_placed_json(local, obj.Placement))


def ball_index_of(obj, kernel_lattice, u, v, w, n):
    """Index into kernel_lattice.balls() of node n of the cell (u, v, w) counted along U, V, W."""
    physical = (u, v, w)
    return kernel_lattice.ball_index(*(physical["UVW".index(a)] for a in obj.AppliedOrder), n)


def _placed_json(local, placement):
    """The lattice's file, moved by the object's placement."""
    import steadylattice as sl
    rotation = placement.Rotation
    g = sl.Similarity.translation(tuple(placement.Base))
    if rotation.Angle != 0.0:
        g = g * sl.Similarity.rotation(rotation.Angle, tuple(rotation.Axis))
    return local.placed(g).to_json()


def export_shape(obj):
    """The shape an export writes for `obj`: its Shape, or for a lattice shown as a preview (empty Shape) its
    balls and beams as solids, built now."""
    if hasattr(obj, "Preset") and not obj.Shape.Solids:
        from latticewb.features import lattice_shape
        shape = lattice_shape.lattice_shape(steady_lattice.build_lattice(obj))
        shape.Placement = obj.Placement
        return shape
    return obj.Shape


def _export_step(objects, path):
    """STEP with one named part per object (FreeCAD's Import keeps labels and colours); a single LatticePart is
    written as an assembly of its skin and its lattice, two named and coloured parts."""
    import Import
    if len(objects) == 1 and hasattr(objects[0], "Policy") and hasattr(objects[0], "Skin"):
        from latticewb.features import lattice_part
        from latticewb.progress import LongOperation
        with LongOperation("Exporting %s" % objects[0].Label) as report:
            lattice_part.write_step_assembly(objects[0], path, report)  # trims again: shows progress, cancellable
        return
    shapes = [export_shape(o) for o in objects]
    if all(shape is o.Shape for shape, o in zip(shapes, objects)):
        Import.export(objects, path)
        return
    # some shapes were built on demand: export named copies from a scratch document
    try:
        scratch = FreeCAD.newDocument("LatticeExport", "LatticeExport", True)  # hidden, where supported
    except TypeError:
        scratch = FreeCAD.newDocument("LatticeExport")
    try:
        copies = []
        for o, shape in zip(objects, shapes):
            copy = scratch.addObject("Part::Feature", o.Name)
            copy.Label = o.Label
            copy.Shape = shape
            copies.append(copy)
        Import.export(copies, path)
    finally:
        FreeCAD.closeDocument(scratch.Name)


def export(objects, path):
    """Writes `objects` to `path`; the format follows the extension:
    .step/.stp (STEP, one part per object with its name; a LatticePart alone: its skin and lattice as two parts),
    .brep/.brp (BREP of the compound),
    .json (the lattice file of a single SteadyLattice).
    Writing a LatticePart's STEP assembly trims it again, with FreeCAD's progress bar; a cancel raises
    steadylattice.Cancelled and writes nothing."""
    objects = list(objects)
    if not objects:
        raise ValueError("objects: nothing to export")
    extension = os.path.splitext(path)[1].lower()
    if extension in (".step", ".stp"):
        _export_step(objects, path)
    elif extension in (".brep", ".brp"):
        import Part
        Part.Compound([export_shape(o) for o in objects]).exportBrep(path)
    elif extension == ".json":
        if len(objects) != 1 or not hasattr(objects[0], "Preset"):
            raise ValueError("objects: a .json lattice file holds exactly one SteadyLattice")
        with open(path, "w") as f:
            f.write(lattice(objects[0]).to_json())
    else:
        raise ValueError("path: unknown format %r (use .step, .stp, .brep, .brp or .json)" % extension)
    if not os.path.isfile(path):
        raise RuntimeError("export: %s was not written" % path)
    return path
