"""Long work reports progress and can be cancelled without changing the document."""
import os
import tempfile
import unittest

import FreeCAD

import steadylattice as sl
from latticewb import api
from latticewb.kernel import lattice_shape
from latticewb.utils.progress import LongOperation


def cancelling_on(predicate):
    """Patches LongOperation so that it cancels (as the Cancel button would) when predicate(fraction) holds;
    returns the fractions seen and the function that undoes the patch."""
    original = LongOperation.__call__
    seen = []

    def call(operation, fraction):
        seen.append(fraction)
        if predicate(fraction):
            operation.cancel()
        return original(operation, fraction)

    LongOperation.__call__ = call
    return seen, lambda: setattr(LongOperation, "__call__", original)


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
        self.assertIn("Touched", obj.State)  # needs a recompute, no error (no traceback for the user)
        self.assertNotIn("Invalid", obj.State)
        self.assertEqual(len(obj.Shape.Solids), 0)  # the previous (preview) shape is kept
        self.assertAlmostEqual(other.Shape.Volume, volume)
        self.doc.recompute()  # without cancelling, it builds
        self.assertEqual(len(obj.Shape.Solids), obj.BallCount + obj.BeamCount)

    def make_part(self):
        lattice = api.make_lattice(self.doc, preset="cubic", cells=(4, 4, 3), cell_size=10.0, node_radius=2.0,
                                   beam_radius=1.0)
        body = self.doc.addObject("Part::Cylinder", "Body")
        body.Radius, body.Height = 17.0, 26.0
        body.Placement.Base = FreeCAD.Vector(20, 20, 2)
        part = api.make_part(self.doc, lattice, body)
        self.doc.recompute()
        self.assertTrue(part.isValid())
        return lattice, body, part

    def test_a_cancelled_part_recompute_keeps_the_document(self):
        lattice, body, part = self.make_part()
        volume, faces, shape_volume = part.Volume, part.FaceCount, part.Shape.Volume
        body.Radius = 14.0  # re-trims (the Booleans against the cylinder last long enough to report)
        seen, restore = cancelling_on(lambda f: f < 1.0)
        try:
            self.doc.recompute()
        finally:
            restore()
        self.assertTrue(seen and seen[0] < 1.0, seen)
        self.assertEqual(part.State, ["Touched"])  # no error (no traceback), marked: recompute to trim
        self.assertIs(self.doc.getObject(part.Name), part)
        self.assertAlmostEqual(part.Shape.Volume, shape_volume, places=6)  # the previous shape stays
        self.assertEqual(len(part.Shape.Faces), faces)
        self.assertAlmostEqual(part.Volume, volume, places=6)
        self.assertTrue(part.Shape.isValid())
        # the document saves and reopens with the previous shape, and trims when recomputed
        path = os.path.join(tempfile.mkdtemp(), "cancelled.FCStd")
        self.doc.saveAs(path)
        name = part.Name
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        again = self.doc.getObject(name)
        self.assertAlmostEqual(again.Shape.Volume, shape_volume, places=6)
        self.assertEqual(again.Body.Radius.Value, 14.0)
        again.touch()
        self.doc.recompute()
        self.assertTrue(again.isValid())
        self.assertLess(again.Volume, volume)  # the smaller body now

    def test_a_cancelled_step_export_writes_nothing(self):
        lattice, body, part = self.make_part()
        path = os.path.join(tempfile.mkdtemp(), "part.step")
        seen, restore = cancelling_on(lambda f: f < 1.0)
        try:
            with self.assertRaises(sl.Cancelled):
                api.export([part], path)
        finally:
            restore()
        self.assertFalse(os.path.exists(path))
        self.assertTrue(part.isValid())
        api.export([part], path)
        self.assertTrue(os.path.exists(path))
