"""LatticeMesh: a steady lattice as a FreeCAD mesh (Mesh::Feature), straight from the kernel: one closed,
oriented, self-intersection-free triangle mesh, for lattices too large for a B-rep and for printing.

Links to a SteadyLattice; Tolerance is the chord error in mm (every vertex lies on the exact surface, every
triangle within Tolerance of it). Meshing shows FreeCAD's progress bar and can be cancelled: a cancelled recompute
keeps the previous mesh and leaves the object touched."""
import os
import tempfile

import FreeCAD

from latticewb.kernel import steady_lattice
from latticewb.objects import feature_checks, property_checks
from latticewb.utils import types
from latticewb.utils.proxies import StatelessProxy, add_missing_properties

_PROPERTIES = [
    ("App::PropertyLink", "Lattice", "Mesh", "The SteadyLattice to mesh"),
    ("App::PropertyLength", "Tolerance", "Mesh",
     "Largest distance from a triangle to the exact surface (chord error), mm; below a quarter of the smallest "
     "ball radius"),
    ("App::PropertyInteger", "TriangleCount", "Result", "Triangles of the mesh (read only)"),
    ("App::PropertyFloat", "Volume", "Result", "Volume enclosed by the mesh in mm^3 (read only)"),
    ("App::PropertyInteger", "DistinctHubs", "Result",
     "Distinct hub shapes, each tessellated once and placed as similar copies (read only)"),
]


class LatticeMesh(StatelessProxy):
    Type = types.LATTICE_MESH

    def __init__(self, obj):
        obj.Proxy = self
        self.ensure_properties(obj)

    @staticmethod
    def ensure_properties(obj):
        fresh = add_missing_properties(obj, _PROPERTIES)
        if "Tolerance" in fresh:
            obj.Tolerance = 0.01
        for name in ("TriangleCount", "Volume", "DistinctHubs"):
            obj.setEditorMode(name, 1)
        property_checks.remember_good(obj)

    def onDocumentRestored(self, obj):
        self.ensure_properties(obj)

    def onChanged(self, obj, prop):
        if hasattr(obj, "DistinctHubs"):  # the last property: not while ensure_properties adds them
            property_checks.check_lattice_property(obj, prop)

    def execute(self, obj):
        import Mesh
        import steadylattice
        from latticewb.utils import progress
        try:
            property_checks.require_sensible(obj)  # names the property, where the kernel would name its own fields
        except ValueError as error:
            FreeCAD.Console.PrintError("%s: %s\n" % (obj.Label, error))
            raise ValueError("%s: %s" % (obj.Label, error)) from None
        # The kernel streams the mesh into a binary STL that FreeCAD's Mesh reads natively: no per-triangle Python.
        handle, path = tempfile.mkstemp(suffix=".stl")
        os.close(handle)
        stats = {}
        try:
            with progress.LongOperation("Meshing %s" % obj.Label) as report:
                steady_lattice.lattice(obj.Lattice).write_stl(path, obj.Tolerance.Value, name=obj.Label,
                                                              progress=report, stats=stats)
            mesh = Mesh.Mesh(path)
        except ValueError as error:
            error = feature_checks.named_kernel_error(error)
            FreeCAD.Console.PrintError("%s: %s\n" % (obj.Label, error))
            raise ValueError("%s: %s" % (obj.Label, error)) from None
        except steadylattice.Cancelled:
            progress.keep_previous_shape(obj, "meshing")
            return
        finally:
            if os.path.exists(path):
                os.remove(path)
        obj.Mesh = mesh
        obj.TriangleCount = stats["triangles"]
        obj.Volume = mesh.Volume
        obj.DistinctHubs = stats["distinct_hubs"]
        property_checks.remember_good(obj)
