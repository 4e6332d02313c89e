"""Issue 16, repro 12: nonsense property values of a SteadyLattice. Each is refused as it is set (the previous
value comes back, a warning names the property), and, when it gets in anyway (no good value known, as in a
document saved by an older version), the recompute fails naming the property and keeps the previous shape."""
import math
import unittest

import FreeCAD

from latticewb import api
from property_editing import Warnings, same

NAN = float("nan")

# (layout, preset, property, nonsense value or a function of the object giving it): every row of the reproducer
# (its first eight), then the other kinds of property of the same object.
ROWS = [
    ("grading", "cubic", "TwistU", NAN),
    ("grading", "cubic", "TaperU", NAN),
    ("grading", "cubic", "CellSize", 1e308),
    ("grading", "cubic", "NodeRadius", 1e308),
    ("grading", "custom", "Beams", ["0 99999999999999999999 0 0 0"]),
    ("grading", "cubic", "CellSize", 1e200),
    ("frames", "cubic", "EndU", FreeCAD.Placement(FreeCAD.Vector(1e308, 0, 0), FreeCAD.Rotation())),
    ("grading", "cubic", "Placement", FreeCAD.Placement(FreeCAD.Vector(NAN, 0, 0), FreeCAD.Rotation())),
    ("steps", "cubic", "StepV", FreeCAD.Placement(FreeCAD.Vector(0, 1, 0), FreeCAD.Rotation(NAN, 0, 0, 1))),
    ("grading", "custom", "NodeRadii", lambda obj: [NAN] + list(obj.NodeRadii)[1:]),
    ("grading", "custom", "Nodes", lambda obj: [FreeCAD.Vector(0, 0, NAN)] + list(obj.Nodes)[1:]),
]


def nonsense(obj, value):
    return value(obj) if callable(value) else value


class NonsensePropertiesTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("NonsenseProperties")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def lattice(self, layout, preset):
        obj = api.make_lattice(self.doc, preset=preset, cells=(2, 2, 2), cell_size=10, node_radius=1.2,
                               beam_radius=0.8)
        obj.Layout = layout
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertTrue(obj.Shape.isValid())
        return obj

    def test_each_nonsense_value_is_refused_when_set_naming_the_property(self):
        for layout, preset, prop, value in ROWS:
            with self.subTest(prop=prop, value=value):
                obj = self.lattice(layout, preset)
                before, volume = getattr(obj, prop), obj.Shape.Volume
                with Warnings() as warnings:
                    setattr(obj, prop, nonsense(obj, value))
                self.assertTrue(same(getattr(obj, prop), before), "%s kept %r" % (prop, getattr(obj, prop)))
                self.assertTrue(any(t.startswith("%s: %s" % (obj.Label, prop)) and "keeping" in t
                                    for t in warnings.texts), warnings.texts)
                self.doc.recompute()
                self.assertTrue(obj.isValid())
                self.assertTrue(obj.Shape.isValid())
                self.assertAlmostEqual(obj.Shape.Volume, volume, places=6)

    def test_a_nonsense_value_that_got_in_fails_the_recompute_naming_it_and_keeps_the_shape(self):
        for layout, preset, prop, value in ROWS:
            with self.subTest(prop=prop, value=value):
                obj = self.lattice(layout, preset)
                volume = obj.Shape.Volume
                obj.Proxy._last_good.clear()  # as after loading a document: no good value to go back to
                with Warnings():
                    setattr(obj, prop, nonsense(obj, value))
                self.doc.recompute()
                self.assertIn("Invalid", obj.State)
                self.assertTrue(obj.getStatusString().startswith("%s: %s" % (obj.Label, prop)),
                                obj.getStatusString())
                if prop != "Placement":  # FreeCAD places the kept shape by the object's Placement itself
                    self.assertTrue(obj.Shape.isValid())
                    self.assertAlmostEqual(obj.Shape.Volume, volume, places=6)

    def test_values_sensible_alone_but_not_together_fail_naming_one_of_them(self):
        cases = [("CellSize", 1e11, {"CellsU": 100}, "spans"),  # 1e13 mm: beyond the supported range
                 ("TaperU", 1000.0, {"CellsU": 400}, "scales by e^"),  # 11^401 overflows
                 ("TwistU", 360.0, {"CellsU": 200000}, "turns")]  # 1.3e6 rad: beyond the supported angle
        for prop, value, others, words in cases:
            with self.subTest(prop=prop):
                obj = api.make_lattice(self.doc, preset="cubic", cells=(2, 1, 1))
                self.doc.recompute()
                volume = obj.Shape.Volume
                for name, v in others.items():
                    setattr(obj, name, v)
                setattr(obj, prop, value)
                self.assertTrue(math.isclose(getattr(obj, prop) if prop == "TaperU" else getattr(obj, prop).Value,
                                             value))
                self.doc.recompute()
                self.assertIn("Invalid", obj.State)
                status = obj.getStatusString()
                self.assertTrue(status.startswith("%s: %s: " % (obj.Label, prop)) and words in status, status)
                self.assertAlmostEqual(obj.Shape.Volume, volume, places=6)


if __name__ == "__main__":
    unittest.main()
