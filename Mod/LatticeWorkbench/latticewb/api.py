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
    "cell_size": "CellSize",
    "node_radius": "NodeRadius",
    "beam_radius": "BeamRadius",
    "step_mode": "StepMode",
    "step_u": "StepU", "step_v": "StepV", "step_w": "StepW",
    "scale_u": "ScaleU", "scale_v": "ScaleV", "scale_w": "ScaleW",
    "nodes": "Nodes", "node_radii": "NodeRadii", "beams": "Beams",
    "placement": "Placement",
}


def make_lattice(doc, preset=None, **params):
    """Adds a SteadyLattice to `doc` and returns it (recompute the document to build it).

    preset: "cubic", "BCC", "FCC", "octet" or "custom" (default octet).
    params: cells=(u, v, w), cell_size, node_radius, beam_radius, step_mode ("incremental" or "cumulative"),
    step_u / step_v / step_w (FreeCAD.Placement, translation in cell units), scale_u / scale_v / scale_w,
    and for a custom cell nodes (list of vectors in cell units), node_radii, beams (strings 'n1 di dj dk n2').
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


def lattice(obj):
    """The steadylattice.Lattice of a SteadyLattice object, placed by the object's Placement."""
    import steadylattice as sl
    local = steady_lattice.build_lattice(obj)
    return sl.Lattice.from_json(_placed_json(local, obj.Placement))


def _placed_json(local, placement):
    """The lattice's file with the object's placement as its G."""
    import json
    import steadylattice as sl
    rotation = placement.Rotation
    g = sl.Similarity.translation(tuple(placement.Base))
    if rotation.Angle != 0.0:
        g = g * sl.Similarity.rotation(rotation.Angle, tuple(rotation.Axis))
    doc = json.loads(local.to_json())
    doc["placement"] = json.loads(g.to_json())
    return json.dumps(doc)


def export(objects, path):
    """Writes `objects` to `path`; the format follows the extension:
    .step/.stp (STEP, one part per object with its name), .brep/.brp (BREP of the compound),
    .json (the lattice file of a single SteadyLattice)."""
    objects = list(objects)
    if not objects:
        raise ValueError("objects: nothing to export")
    extension = os.path.splitext(path)[1].lower()
    if extension in (".step", ".stp"):
        import Import
        Import.export(objects, path)
    elif extension in (".brep", ".brp"):
        import Part
        Part.Compound([o.Shape for o in objects]).exportBrep(path)
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
