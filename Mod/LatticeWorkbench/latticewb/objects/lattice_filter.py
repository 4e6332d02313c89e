"""LatticeFilter: which nodes of a lattice exist, decided by a filter; beams stay where both their nodes do.

The source is a SteadyLattice or another LatticeFilter (filters cascade: each one further thins its source).
Kinds:
  stencil             keep node (i, j, k) when StencilMask says so, repeating with period StencilSize
  lattice-in-lattice  keep a node whose ball meets the Coarse lattice (a SteadyLattice or LatticeFilter)
  gyroid              keep a node inside a gyroid sheet (or solid) of the given period and thickness
  inside body         keep a node whose centre is inside the Body (a solid; several solids: their union)
Invert keeps the complement. Nothing is stored per element: the kernel evaluates the filter on demand.
"""
import FreeCAD

from latticewb.kernel import lattice_shape
from latticewb.kernel.lattice_filter import GYROID_MODES, KINDS, filtered_lattice
from latticewb.objects import property_checks
from latticewb.utils import types
from latticewb.utils.proxies import StatelessProxy, add_missing_properties

_PROPERTIES = [
    ("App::PropertyLink", "Source", "Filter", "The lattice to filter: a SteadyLattice or another LatticeFilter"),
    ("App::PropertyEnumeration", "Kind", "Filter", "Which nodes to keep (see the Stencil, Coarse, Gyroid, Body entries)"),
    ("App::PropertyBool", "Invert", "Filter", "Keep the nodes the filter would drop"),
    ("App::PropertyIntegerList", "StencilSize", "Stencil", "Period of the stencil along the lattice's i, j, k"),
    ("App::PropertyString", "StencilMask", "Stencil",
     "One character per cell of the period, i fastest then j then k: 1 keeps, 0 drops (e.g. '10' with size 2 1 1)"),
    ("App::PropertyLink", "Coarse", "Lattice in lattice",
     "Keep the nodes whose balls meet this coarse lattice (a SteadyLattice or LatticeFilter)"),
    ("App::PropertyLength", "GyroidPeriod", "Gyroid", "Period of the gyroid field"),
    ("App::PropertyFloat", "GyroidThickness", "Gyroid", "Half-thickness of the sheet in field units (0 to 1.5)"),
    ("App::PropertyEnumeration", "GyroidMode", "Gyroid", "sheet: |g| <= thickness; solid: g <= thickness"),
    ("App::PropertyLink", "Body", "Inside body", "Keep the nodes whose centres are inside this solid (several solids: inside any of them)"),
    ("App::PropertyInteger", "BallCount", "Result", "Balls kept (read only)"),
    ("App::PropertyInteger", "BeamCount", "Result", "Beams kept (read only)"),
]


class LatticeFilter(StatelessProxy):
    Type = types.LATTICE_FILTER

    def __init__(self, obj):
        obj.Proxy = self
        self.ensure_properties(obj)

    @staticmethod
    def ensure_properties(obj):
        fresh = add_missing_properties(obj, _PROPERTIES)
        if "Kind" in fresh:
            obj.Kind = KINDS
            obj.Kind = "stencil"
        if "StencilSize" in fresh:
            obj.StencilSize = [2, 1, 1]
        if "StencilMask" in fresh:
            obj.StencilMask = "10"
        if "GyroidPeriod" in fresh:
            obj.GyroidPeriod = 20.0
        if "GyroidThickness" in fresh:
            obj.GyroidThickness = 0.4
        if "GyroidMode" in fresh:
            obj.GyroidMode = GYROID_MODES
            obj.GyroidMode = "sheet"
        for name in ("BallCount", "BeamCount"):
            obj.setEditorMode(name, 1)
        property_checks.remember_good(obj)

    def onDocumentRestored(self, obj):
        self.ensure_properties(obj)

    def onChanged(self, obj, prop):
        if hasattr(obj, "BeamCount"):  # the last property: not while ensure_properties adds them
            property_checks.check_lattice_property(obj, prop)

    def execute(self, obj):
        try:
            property_checks.require_sensible(obj)  # names the property, where the kernel would name its own fields
            filtered = filtered_lattice(obj)
            ball_mask, beam_mask = filtered.ball_mask(), filtered.beam_mask()
        except ValueError as error:
            FreeCAD.Console.PrintError("%s: %s\n" % (obj.Label, error))
            raise ValueError("%s: %s" % (obj.Label, error)) from None
        self.view = (filtered.lattice, ball_mask, beam_mask)  # for the view provider's preview
        property_checks.remember_good(obj)
        obj.BallCount = int(ball_mask.sum())
        obj.BeamCount = int(beam_mask.sum())
        if obj.BallCount + obj.BeamCount <= lattice_shape.MAX_SOLID_ELEMENTS:
            obj.Shape = lattice_shape.lattice_shape(filtered.lattice, ball_mask=ball_mask, beam_mask=beam_mask)
        else:
            obj.Shape = lattice_shape.empty_shape()

    def preview_data(self, obj):
        view = getattr(self, "view", None)
        if view is None:
            try:
                filtered = filtered_lattice(obj)
                view = self.view = (filtered.lattice, filtered.ball_mask(), filtered.beam_mask())
            except ValueError:
                return None
        return view
