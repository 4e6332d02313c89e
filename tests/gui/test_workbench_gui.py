"""The workbench in a real FreeCAD window: it activates, its command builds a lattice, the view shows it."""
import unittest

import time

import FreeCAD
import FreeCADGui
from PySide import QtGui

from latticewb.taskpanels import lattice_task_panel
from screenshots import ink_fraction, save_view, save_window


def wait_for_recompute(seconds=1.0):
    """Lets the task panel's debounce timer fire and the view update."""
    end = time.time() + seconds
    while time.time() < end:
        QtGui.QApplication.processEvents()
        time.sleep(0.02)


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
        lattice_task_panel.active_panel.accept()
        obj = self.doc.Objects[0]
        self.assertTrue(obj.isValid())
        self.assertGreater(obj.BeamCount, 0)
        # the property editor's parameters drive it: a twist and taper along W
        obj.StepW = FreeCAD.Placement(FreeCAD.Vector(0, 0, 1), FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), 6))
        obj.ScaleW = 0.95
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        path = save_view("guide_steady_lattice")
        ink, colours = ink_fraction(path)
        self.assertGreater(ink, 0.05, "the lattice should cover a visible part of the view")
        self.assertLess(ink, 0.95, "the view should not be one flat colour")
        self.assertGreater(colours, 5, "a shaded lattice has many tones")
        # an empty document draws nothing
        obj.Visibility = False
        FreeCADGui.updateGui()
        empty, _ = ink_fraction(save_view("empty"))
        self.assertLess(empty, 0.02)

    def test_task_panel_edits_live_and_cancel_restores(self):
        FreeCADGui.activateWorkbench("LatticeWorkbench")
        FreeCADGui.runCommand("Lattice_NewLattice")
        panel = lattice_task_panel.active_panel
        obj = self.doc.Objects[0]
        beams = obj.BeamCount
        panel.fields["CellsU"][0].setValue(obj.CellsU + 2)
        panel.fields["TwistW"][0].setValue(5.0)
        wait_for_recompute()
        self.assertEqual(obj.CellsU, 5)
        self.assertGreater(obj.BeamCount, beams)  # recomputed live
        self.assertAlmostEqual(obj.TwistW.Value, 5.0)
        self.assertIn("balls", panel.status.text())
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.activeDocument().activeView().viewIsometric()
        FreeCADGui.SendMsgToActiveView("ViewFit")
        ink, _ = ink_fraction(save_window("guide_task_panel"))
        self.assertGreater(ink, 0.05)
        panel.reject()  # the panel created the lattice: cancelling removes it
        self.assertEqual(len(self.doc.Objects), 0)

    def test_editing_an_existing_lattice_is_one_undo_step(self):
        FreeCADGui.activateWorkbench("LatticeWorkbench")
        from latticewb import api
        self.doc.UndoMode = 1
        self.doc.openTransaction("make")
        obj = api.make_lattice(self.doc, preset="BCC", cells=(2, 2, 2))
        self.doc.commitTransaction()
        self.doc.recompute()
        FreeCADGui.ActiveDocument.setEdit(obj.Name, 0)
        panel = lattice_task_panel.active_panel
        self.assertIsNotNone(panel)
        panel.fields["TaperU"][0].setValue(-5.0)
        panel.fields["BeamRadius"][0].setValue(50.0)  # wider than the nodes: clamped, and the widget shows it
        wait_for_recompute()
        self.assertAlmostEqual(obj.BeamRadius.Value, obj.NodeRadius.Value)
        self.assertAlmostEqual(panel.fields["BeamRadius"][0].value(), obj.NodeRadius.Value)
        panel.accept()
        self.assertAlmostEqual(obj.TaperU, -5.0)
        self.doc.undo()
        self.assertAlmostEqual(obj.TaperU, 0.0)
        self.assertAlmostEqual(obj.BeamRadius.Value, 0.8)

    def test_properties_report_command(self):
        from latticewb import api
        FreeCADGui.activateWorkbench("LatticeWorkbench")
        obj = api.make_lattice(self.doc, preset="BCC", cells=(2, 2, 2), node_radius=1.5, beam_radius=0.6)
        obj.Density = 4.43
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(obj)
        FreeCADGui.runCommand("Lattice_Properties")
        wait_for_recompute(0.3)
        boxes = [w for w in QtGui.QApplication.topLevelWidgets()
                 if isinstance(w, QtGui.QMessageBox) and w.isVisible()]
        self.assertEqual(len(boxes), 1)
        text = boxes[0].text()
        self.assertIn("closed form", text)
        self.assertIn("%.6g mm^3" % api.properties(obj)["volume"], text)
        boxes[0].close()
