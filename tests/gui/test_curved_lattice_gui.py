"""The CurvedLattice command in a real FreeCAD window: four selected vertices become its linked corners, the view
shows it, and the Lattice part command trims it into a cylinder with the bridge policy."""
import math
import unittest

import FreeCAD
import FreeCADGui

from latticewb.utils import types
from screenshots import ink_fraction, save_view


class CurvedLatticeGuiTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("CurvedGui")
        FreeCADGui.activateWorkbench("LatticeWorkbench")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_four_selected_vertices_become_the_corners_then_a_bridged_part(self):
        turn = math.radians(160.0)
        points = [(7, 0), (24, 0), (24 * math.cos(turn), 24 * math.sin(turn)), (7 * math.cos(turn), 7 * math.sin(turn))]
        vertices = []
        for k, (x, y) in enumerate(points):
            v = self.doc.addObject("Part::Vertex", "Corner%d" % k)
            v.X, v.Y, v.Z = x, y, 1.0
            vertices.append(v)
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        for v in vertices:
            FreeCADGui.Selection.addSelection(v)
        FreeCADGui.runCommand("Lattice_NewCurvedLattice")
        curved = [o for o in self.doc.Objects if types.is_curved_lattice(o)]
        self.assertEqual(len(curved), 1)
        obj = curved[0]
        self.assertEqual([obj.ALink[0], obj.BLink[0], obj.CLink[0], obj.DLink[0]], vertices)
        obj.NodeRadius, obj.CellsU, obj.CellsV, obj.Layers, obj.LayerRaise = 0.35, 8, 6, 2, 2.5
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        FreeCADGui.Selection.clearSelection()
        ink, colours = ink_fraction(save_view("curved_lattice"))
        self.assertGreater(ink, 0.02)
        self.assertGreater(colours, 5)
        body = self.doc.addObject("Part::Cylinder", "Body")
        body.Radius, body.Height = 20.0, 22.0
        body.Placement.Base = FreeCAD.Vector(0, 0, -1)
        self.doc.recompute()
        FreeCADGui.Selection.addSelection(obj)
        FreeCADGui.Selection.addSelection(body)
        FreeCADGui.runCommand("Lattice_Part")
        parts = [o for o in self.doc.Objects if types.is_part(o)]
        self.assertEqual(len(parts), 1)
        parts[0].Policy = "bridge"
        self.doc.recompute()
        self.assertTrue(parts[0].isValid(), parts[0].getStatusString())
        self.assertEqual(len(parts[0].Shape.Solids), 1)

    def test_a_selected_face_lays_the_lattice_on_it(self):
        body = self.doc.addObject("Part::Cylinder", "Body")
        body.Radius, body.Height = 20.0, 40.0
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(body, "Face1")
        FreeCADGui.runCommand("Lattice_NewCurvedLattice")
        curved = [o for o in self.doc.Objects if types.is_curved_lattice(o)]
        self.assertEqual(len(curved), 1)
        obj = curved[0]
        self.assertEqual(obj.FaceLink[0], body)
        self.assertEqual(list(obj.FaceLink[1]), ["Face1"])
        obj.NodeRadius, obj.Layers, obj.LayerOffset = 0.8, 2, 3.0
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        from latticewb.kernel import curved_lattice
        lat = curved_lattice.lattice(obj)
        centers, _ = lat.balls()
        first = [lat.ball_index(i, j, 0, 0) for i in range(obj.CellsU) for j in range(obj.CellsV)]
        second = [lat.ball_index(i, j, 1, 0) for i in range(obj.CellsU) for j in range(obj.CellsV)]
        self.assertLess(max(abs(math.hypot(*centers[n][:2]) - 20.0) for n in first), 1e-9)
        self.assertLess(max(abs(math.hypot(*centers[n][:2]) - 17.0) for n in second), 1e-9)
        FreeCADGui.Selection.clearSelection()
        ink, colours = ink_fraction(save_view("curved_lattice_on_face"))
        self.assertGreater(ink, 0.02)


if __name__ == "__main__":
    unittest.main()
