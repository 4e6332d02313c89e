"""make_filter: a LatticeFilter of a lattice (filters cascade), and its view provider when the GUI is up."""
import FreeCAD

from latticewb.kernel.lattice_filter import KINDS
from latticewb.objects.lattice_filter import LatticeFilter
from latticewb.utils import types

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
    if not types.is_lattice_source(source):
        raise ValueError("source: expected a SteadyLattice or LatticeFilter")
    if kind not in KINDS:
        raise ValueError("kind: expected one of %s (got %r)" % (", ".join(KINDS), kind))
    unknown = set(params) - set(_FILTER_PARAMETERS)
    if unknown:
        raise ValueError("%s: unknown parameter (known: %s)" % (sorted(unknown)[0], ", ".join(_FILTER_PARAMETERS)))
    obj = doc.addObject("Part::FeaturePython", "LatticeFilter")
    LatticeFilter(obj)
    obj.Source = source
    obj.Kind = kind
    for key, value in params.items():
        setattr(obj, _FILTER_PARAMETERS[key], list(value) if key == "stencil_size" else value)
    if FreeCAD.GuiUp:
        from latticewb.viewproviders import view_providers
        view_providers.ViewProviderLatticeFilter(obj.ViewObject)
        source.ViewObject.Visibility = False
    return obj
