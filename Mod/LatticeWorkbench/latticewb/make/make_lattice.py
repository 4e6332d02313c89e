"""make_lattice: a SteadyLattice with its parameters, and its view provider when the GUI is up."""
import FreeCAD

from latticewb.objects.steady_lattice import SteadyLattice

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



def make_steady_lattice(doc, name="SteadyLattice"):
    """Adds a SteadyLattice with its defaults to `doc` (with a view provider when the GUI is up) and returns it."""
    obj = doc.addObject("Part::FeaturePython", name)
    SteadyLattice(obj)
    if FreeCAD.GuiUp:
        from latticewb.viewproviders import view_providers
        view_providers.ViewProviderSteadyLattice(obj.ViewObject)
    return obj


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
    obj = make_steady_lattice(doc)
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
