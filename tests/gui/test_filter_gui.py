"""The Filter command in a real window: a fine lattice and a coarse one selected give a Lattice-in-Lattice."""
import unittest

import FreeCAD
import FreeCADGui

from latticewb import api
from screenshots import ink_fraction, save_view


class FilterGuiTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("FilterGuiTest")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_lattice_in_lattice_command(self):
        FreeCADGui.activateWorkbench("LatticeWorkbench")
        fine = api.make_lattice(self.doc, preset="cubic", cells=(24, 24, 12), cell_size=1.25, node_radius=0.22,
                                beam_radius=0.12)
        coarse = api.make_lattice(self.doc, preset="octet", cells=(2, 2, 1), cell_size=15.0, node_radius=1.6,
                                  beam_radius=1.2)
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(fine)
        FreeCADGui.Selection.addSelection(coarse)
        FreeCADGui.runCommand("Lattice_Filter")
        filters = [o for o in self.doc.Objects if hasattr(o, "StencilMask")]
        self.assertEqual(len(filters), 1)
        flt = filters[0]
        self.assertEqual(flt.Kind, "lattice-in-lattice")
        self.assertTrue(flt.isValid())
        self.assertGreater(flt.BeamCount, 0)
        self.assertLess(flt.BeamCount, fine.BeamCount)
        coarse.ViewObject.Visibility = False
        FreeCADGui.Selection.clearSelection()
        ink, _ = ink_fraction(save_view("guide_lattice_in_lattice"))
        self.assertGreater(ink, 0.03)
