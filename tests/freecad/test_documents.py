"""Documents saved by earlier versions of the workbench open, are recognised by their type tags and recompute to
the same results. data/before_layers.FCStd was saved before the workbench was layered (its proxies name the old
modules latticewb.features.*, and they saved no type tag): a BCC lattice of 2 x 2 x 1 cells whose steps apply in
the order W U V, a gyroid filter of it, and a part clipping it by a box (22 balls, 32 beams, 128.649 mm^3)."""
import os
import unittest

import FreeCAD

from latticewb import api

HERE = os.path.dirname(os.path.abspath(__file__))


class OldDocumentsTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.openDocument(os.path.join(HERE, "data", "before_layers.FCStd"))

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_objects_load_with_their_types_and_recompute_the_same(self):
        types = {o.Name: api.get_type(o) for o in self.doc.Objects}
        self.assertEqual(types["SteadyLattice"], "SteadyLattice")
        self.assertEqual(types["LatticeFilter"], "LatticeFilter")
        self.assertEqual(types["LatticePart"], "LatticePart")
        self.assertIsNone(types["Body"])
        for obj in self.doc.Objects:
            obj.touch()
        self.doc.recompute()
        lattice, part = self.doc.getObject("SteadyLattice"), self.doc.getObject("LatticePart")
        self.assertEqual((lattice.BallCount, lattice.BeamCount, lattice.AppliedOrder), (22, 32, "WUV"))
        self.assertTrue(part.Shape.isValid())
        self.assertAlmostEqual(part.Volume, 128.64906824862302, delta=1e-6 * 128.649)
        # the kernel lattice counts cells along U, V, W, with the steps applied in the stored order
        kernel = api.lattice(lattice)
        self.assertEqual(kernel.order, "WUV")
        self.assertEqual(kernel.counts, (3, 3, 2))
