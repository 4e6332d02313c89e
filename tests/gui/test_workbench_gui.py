"""The workbench in a real FreeCAD window: it activates, its command builds a lattice, the view shows it."""
import unittest

import FreeCAD
import FreeCADGui

from screenshots import ink_fraction, save_view


class WorkbenchGuiTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("GuiTest")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_workbench_activates_with_its_toolbar(self):
        FreeCADGui.activateWorkbench("LatticeWorkbench")
        self.assertEqual(FreeCADGui.activeWorkbench().name(), "LatticeWorkbench")
        self.assertIn("Lattice_NewLattice", FreeCADGui.listCommands())

    def test_new_lattice_command_shows_a_lattice(self):
        FreeCADGui.activateWorkbench("LatticeWorkbench")
        FreeCADGui.runCommand("Lattice_NewLattice")
        self.assertEqual(len(self.doc.Objects), 1)
        obj = self.doc.Objects[0]
        self.assertTrue(obj.isValid())
        self.assertGreater(obj.BeamCount, 0)
        # the property editor's parameters drive it: a twist and taper along W
        obj.StepW = FreeCAD.Placement(FreeCAD.Vector(0, 0, 1), FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), 6))
        obj.ScaleW = 0.95
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        path = save_view("steady_lattice")
        ink, colours = ink_fraction(path)
        self.assertGreater(ink, 0.05, "the lattice should cover a visible part of the view")
        self.assertLess(ink, 0.95, "the view should not be one flat colour")
        self.assertGreater(colours, 5, "a shaded lattice has many tones")
        # an empty document draws nothing
        obj.Visibility = False
        FreeCADGui.updateGui()
        empty, _ = ink_fraction(save_view("empty"))
        self.assertLess(empty, 0.02)
