"""The Lattice part command in a real window: select a lattice and a body, press the command, get one valid solid
with a skin; the picture shows the skin half transparent over the lattice."""
import unittest

import FreeCAD
import FreeCADGui

from latticewb import api
from screenshots import ink_fraction, save_view, save_window


class LatticePartGuiTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("PartGuiTest")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_part_command_trims_into_the_selected_body(self):
        FreeCADGui.activateWorkbench("LatticeWorkbench")
        lattice = api.make_lattice(self.doc, preset="octet", cells=(5, 5, 3), cell_size=8.0, node_radius=1.3,
                                   beam_radius=0.55, twist_w=3.0, taper_w=-1.5)
        body = self.doc.addObject("Part::Cylinder", "Body")
        body.Radius, body.Height = 17.0, 22.0
        body.Placement.Base = FreeCAD.Vector(20.0, 20.0, 1.0)
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(lattice)
        FreeCADGui.Selection.addSelection(body)
        FreeCADGui.runCommand("Lattice_Part")
        parts = [o for o in self.doc.Objects if hasattr(o, "Policy")]
        self.assertEqual(len(parts), 1)
        part = parts[0]
        part.Skin = 1.2
        self.doc.recompute()
        self.assertTrue(part.isValid())
        self.assertEqual(len(part.Shape.Solids), 1)
        self.assertTrue(part.Shape.isValid())
        self.assertFalse(lattice.ViewObject.Visibility)  # inputs hidden, like a Boolean's
        self.assertEqual(set(part.ViewObject.Proxy.claimChildren()), {lattice, body})
        part.ViewObject.Transparency = 55
        FreeCADGui.Selection.clearSelection()
        ink, colours = ink_fraction(save_view("guide_lattice_part"))
        self.assertGreater(ink, 0.05)
        self.assertGreater(colours, 5)
        FreeCADGui.Selection.addSelection(part)
        save_window("guide_lattice_part_window")
        # without a skin: the lattice clipped at the cylinder
        part.Skin = 0.0
        part.ViewObject.Transparency = 0
        self.doc.recompute()
        self.assertTrue(part.isValid() and part.Shape.isValid())
        FreeCADGui.Selection.clearSelection()
        ink, _ = ink_fraction(save_view("guide_lattice_part_clip"))
        self.assertGreater(ink, 0.05)
        # undo removes the part in one step
        self.doc.undo() if self.doc.UndoCount else None
