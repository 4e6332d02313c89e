"""Long work reports progress and can be cancelled without changing the document."""
import unittest

import FreeCAD

import steadylattice as sl
from latticewb import api
from latticewb.features import lattice_shape
from latticewb.progress import LongOperation


class ProgressTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("ProgressTest")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_reports_grow_and_cancelling_stops_the_work(self):
        obj = api.make_lattice(self.doc, preset="octet", cells=(6, 6, 6), representation="Preview")
        self.doc.recompute()
        lattice = api.lattice(obj)
        seen = []
        lattice_shape.lattice_shape(lattice, report=lambda f: seen.append(f) or True)
        self.assertGreater(len(seen), 3)
        self.assertEqual(seen, sorted(seen))
        stopped_at = []
        with self.assertRaises(sl.Cancelled):
            lattice_shape.lattice_shape(lattice, report=lambda f: stopped_at.append(f) or f < 0.3)
        self.assertLess(stopped_at[-1], 0.5)

    def test_a_cancelled_recompute_keeps_the_document(self):
        other = api.make_lattice(self.doc, preset="cubic", cells=(2, 2, 2))
        obj = api.make_lattice(self.doc, preset="octet", cells=(6, 6, 6), representation="Preview")
        self.doc.recompute()
        volume = other.Shape.Volume
        obj.Representation = "Elements"
        original = LongOperation.__call__
        LongOperation.__call__ = lambda self, f: (self.cancel() if f > 0.2 else None) or original(self, f)
        try:
            self.doc.recompute()
        finally:
            LongOperation.__call__ = original
        self.assertIn("Invalid", obj.State)
        self.assertEqual(len(obj.Shape.Solids), 0)  # the previous (preview) shape is kept
        self.assertAlmostEqual(other.Shape.Volume, volume)
        self.doc.recompute()  # without cancelling, it builds
        self.assertEqual(len(obj.Shape.Solids), obj.BallCount + obj.BeamCount)
