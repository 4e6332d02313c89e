"""The Lattice mesh command in a real window: select a dense octet, press the command, get one closed mesh drawn
by FreeCAD's mesh view provider; the picture is the one in docs/mesh.md."""
import unittest

import FreeCAD
import FreeCADGui

from latticewb import api
from screenshots import ink_fraction, save_view


class LatticeMeshGuiTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("MeshGuiTest")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_mesh_command_meshes_the_selected_lattice(self):
        FreeCADGui.activateWorkbench("LatticeWorkbench")
        # beams 0.7 of their nodes: every hub crowded, built as a radial graph around its ball
        lattice = api.make_lattice(self.doc, preset="octet", cells=(3, 3, 2), cell_size=8.0, node_radius=1.6,
                                   beam_radius=1.12, twist_w=4.0)
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(lattice)
        FreeCADGui.runCommand("Lattice_Mesh")
        meshes = [o for o in self.doc.Objects if api.get_type(o) == "LatticeMesh"]
        self.assertEqual(len(meshes), 1)
        mesh = meshes[0]
        mesh.Tolerance = 0.02
        self.doc.recompute()
        self.assertTrue(mesh.Mesh.isSolid())
        self.assertFalse(mesh.Mesh.hasNonManifolds())
        self.assertFalse(lattice.ViewObject.Visibility)
        self.assertEqual(mesh.ViewObject.Proxy.claimChildren(), [lattice])
        mesh.ViewObject.ShapeColor = (0.85, 0.55, 0.20)
        FreeCADGui.Selection.clearSelection()
        ink, colours = ink_fraction(save_view("lattice_mesh"))
        self.assertGreater(ink, 0.05)
        self.assertGreater(colours, 5)


if __name__ == "__main__":
    unittest.main()
