"""The scalable preview in a real window: a lattice of about 10^6 beams is drawn as lines and points, within the
budget, and hiding the object hides it. (Its timings are measured by tests/bench/bench_preview.py.)"""
import unittest

import FreeCAD
import FreeCADGui

from latticewb import api
from screenshots import ink_fraction, save_view


class PreviewGuiTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("PreviewTest")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_million_beam_preview(self):
        obj = api.make_lattice(self.doc, preset="octet", cells=(35, 35, 35), cell_size=4.0, node_radius=0.6,
                               beam_radius=0.4, twist_w=1.0, taper_w=-0.5)
        self.doc.recompute()
        self.assertGreater(obj.BeamCount, 1000000)
        self.assertEqual(len(obj.Shape.Solids), 0)
        preview = obj.ViewObject.Proxy.preview
        self.assertEqual(preview.drawn_beams, obj.BeamCount)
        self.assertEqual(preview.lines.coordIndex.getNum(), 3 * obj.BeamCount)
        self.assertEqual(preview.coordinates.point.getNum(), obj.BallCount)
        ink, _ = ink_fraction(save_view("guide_preview_million"))
        self.assertGreater(ink, 0.1)
        # the budget bounds what is drawn
        obj.PreviewBudget = 100000
        self.doc.recompute()
        self.assertLessEqual(preview.drawn_beams, 100000)
        self.assertGreater(preview.drawn_beams, 90000)
        # hiding the object hides the preview
        obj.ViewObject.Visibility = False
        FreeCADGui.updateGui()
        hidden, _ = ink_fraction(save_view("preview_hidden"))
        self.assertLess(hidden, 0.02)

    def test_bent_lattice_screenshot(self):
        api.make_lattice(self.doc, preset="octet", cells=(10, 3, 3), cell_size=6.0, node_radius=0.9,
                         beam_radius=0.55, bend_u=6.0, bend_u_toward="V", taper_u=-2.0, representation="Elements")
        self.doc.recompute()
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.activeDocument().activeView().viewTop()
        ink, colours = ink_fraction(save_view("guide_bent_lattice", isometric=False))
        self.assertGreater(ink, 0.05)
        self.assertGreater(colours, 5)
