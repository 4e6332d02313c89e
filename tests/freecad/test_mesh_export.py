"""Printer files from the workbench, read back by FreeCAD's own Mesh module (STL, OBJ: a solid, manifold, no
self-intersection, the exact volume within the chord bound) and by lib3mf (3MF beam lattices, clipped by a
part's body)."""
import os
import tempfile
import unittest

import FreeCAD
import Mesh

import steadylattice as sl
from latticewb import api
from latticewb.kernel import mesh_export, steady_lattice


class MeshExportTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("MeshExportTest")
        self.folder = tempfile.mkdtemp()
        # an octet with beams 0.6 of their nodes: crowded hubs, built as radial unions
        self.lattice = api.make_lattice(self.doc, preset="octet", cells=(2, 2, 2), cell_size=6.0, node_radius=1.0,
                                        beam_radius=0.6)
        self.doc.recompute()

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_stl_and_obj_are_solid_meshes_for_freecad(self):
        kernel_lattice = steady_lattice.lattice(self.lattice)
        exact = kernel_lattice.properties()["volume"]
        tolerance = mesh_export.default_tolerance(kernel_lattice)
        for extension in (".stl", ".obj"):
            path = api.export([self.lattice], os.path.join(self.folder, "octet" + extension))
            mesh = Mesh.Mesh(path)
            self.assertTrue(mesh.isSolid(), extension)
            self.assertFalse(mesh.hasNonManifolds(), extension)
            self.assertFalse(mesh.hasSelfIntersections(), extension)
            self.assertEqual(len(mesh.getSeparateComponents()), 1)
            self.assertLessEqual(mesh.Volume, exact * (1 + 1e-6))
            self.assertGreaterEqual(mesh.Volume, exact - tolerance * mesh.Area)

    def test_3mf_beam_lattice_with_its_mesh(self):
        path = api.export([self.lattice], os.path.join(self.folder, "octet.3mf"))
        back = sl.read_3mf(path)
        representation, lattice = back["objects"]
        self.assertEqual(len(lattice["beams"]), self.lattice.BeamCount)
        self.assertEqual(len(lattice["vertices"]), self.lattice.BallCount)
        self.assertGreater(len(representation["triangles"]), 0)

    def test_part_goes_to_3mf_clipped_by_its_body(self):
        body = self.doc.addObject("Part::Cylinder", "Body")
        body.Radius, body.Height = 5.0, 10.0
        body.Placement.Base = FreeCAD.Vector(6, 6, 1)
        part = api.make_part(self.doc, self.lattice, body)
        self.doc.recompute()
        path = api.export([part], os.path.join(self.folder, "part.3mf"))
        clipping, lattice = sl.read_3mf(path)["objects"]
        self.assertEqual(len(lattice["beams"]), self.lattice.BeamCount)
        # the body's mesh, closed: every edge used twice
        edges = {}
        for t in clipping["triangles"].tolist():
            for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
                key = (min(a, b), max(a, b))
                edges[key] = edges.get(key, 0) + 1
        self.assertTrue(edges and all(n == 2 for n in edges.values()))

    def test_part_goes_to_stl_trimmed_with_its_skin(self):
        body = self.doc.addObject("Part::Cylinder", "Body")
        body.Radius, body.Height = 5.0, 10.0
        body.Placement.Base = FreeCAD.Vector(6, 6, 1)
        part = api.make_part(self.doc, self.lattice, body, skin=0.8)
        self.doc.recompute()
        path = api.export([part], os.path.join(self.folder, "part.stl"))
        mesh = Mesh.Mesh(path)
        self.assertTrue(mesh.isSolid())
        self.assertFalse(mesh.hasNonManifolds())
        # (FreeCAD's hasSelfIntersections, an approximate test, flags a few of the Boolean's slivers on the body's
        # faces that CGAL's exact predicates find apart, in doubles and in floats: tests/kernel/test_trimmed_mesh.cpp)
        # the exact part (B-rep, adaptive volume) against the mesh: inscribed within the chord bound
        tolerance = mesh_export.default_tolerance(steady_lattice.lattice(self.lattice))
        self.assertLessEqual(mesh.Volume, part.Volume * (1 + 1e-3))
        self.assertGreaterEqual(mesh.Volume, part.Volume - 2 * tolerance * mesh.Area)


class LatticeMeshFeatureTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("LatticeMeshTest")
        self.lattice = api.make_lattice(self.doc, preset="BCC", cells=(3, 3, 3), cell_size=6.0, node_radius=1.0,
                                        beam_radius=0.5)
        self.doc.recompute()

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_mesh_feature_follows_its_lattice_and_survives_reload(self):
        mesh = api.make_mesh(self.doc, self.lattice, tolerance=0.02)
        self.doc.recompute()
        self.assertEqual(api.get_type(mesh), "LatticeMesh")
        self.assertTrue(mesh.Mesh.isSolid() and not mesh.Mesh.hasNonManifolds())
        self.assertEqual(mesh.Mesh.CountFacets, mesh.TriangleCount)
        exact = steady_lattice.lattice(self.lattice).properties()["volume"]
        self.assertLessEqual(mesh.Volume, exact)
        self.assertGreaterEqual(mesh.Volume, exact - 0.02 * mesh.Mesh.Area)
        # editing the lattice re-meshes
        before = mesh.Volume
        self.lattice.NodeRadius = 1.2
        self.doc.recompute()
        self.assertGreater(mesh.Volume, before)
        # nonsense: a tolerance larger than a quarter of the balls is an error with a message, the document stays
        mesh.Tolerance = 5.0
        self.doc.recompute()
        self.assertIn("Invalid", mesh.State)
        mesh.Tolerance = 0.02
        self.doc.recompute()
        self.assertNotIn("Invalid", mesh.State)
        path = os.path.join(tempfile.mkdtemp(), "mesh.FCStd")
        name = mesh.Name
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        restored = self.doc.getObject(name)
        self.assertEqual(api.get_type(restored), "LatticeMesh")
        self.assertEqual(restored.Mesh.CountFacets, restored.TriangleCount)

    def test_bad_input(self):
        with self.assertRaisesRegex(ValueError, "tolerance"):
            api.make_mesh(self.doc, self.lattice, tolerance=-1.0)
        with self.assertRaisesRegex(ValueError, "lattice"):
            api.make_mesh(self.doc, None)


if __name__ == "__main__":
    unittest.main()
