"""Issue 16: nonsense property values of the features made from a lattice (LatticeFilter, LatticePart,
LatticeMesh), as a user can type them in the property editor or the Python console. Each is refused as it is set
(the previous value comes back, a warning names the property) or, for links and for values only the kernel can
judge, fails the recompute with an error naming the property; the previous result is kept, and a good value
afterwards recomputes fine. The SteadyLattice's own rows are in test_nonsense_properties.py."""
import unittest

import FreeCAD

from latticewb import api
from property_editing import Warnings, same
from latticewb.objects import feature_checks

NAN = float("nan")


def box(doc, obj):
    return doc.getObject("Box")


def new(doc, kind, name):
    return doc.addObject(kind, name)


# (feature, property, nonsense: a value or a function (doc, obj) giving it, refused as it is set)
ROWS = [
    ("stencil", "Source", None, False),
    ("stencil", "Source", box, False),  # not a lattice
    ("stencil", "Source", lambda doc, obj: obj, True),  # itself: a cycle
    ("stencil", "Kind", ["voronoi", "random"], True),  # the list of choices replaced from the console
    ("stencil", "StencilSize", [0, 1, 1], True),
    ("stencil", "StencilSize", [2, 1], True),
    ("stencil", "StencilSize", [1000000, 1000000, 1000000], True),
    ("stencil", "StencilMask", "1x", False),  # judged with StencilSize, at recompute
    ("coarse", "Coarse", None, False),
    ("coarse", "Coarse", box, False),
    ("gyroid", "GyroidPeriod", 0.0, True),
    ("gyroid", "GyroidPeriod", NAN, True),
    ("gyroid", "GyroidPeriod", 1e308, True),
    ("gyroid", "GyroidThickness", NAN, True),
    ("gyroid", "GyroidThickness", -1.0, True),  # a sheet keeps |g| <= -1: nothing
    ("gyroid", "GyroidThickness", 5.0, True),  # |g| <= 5: everything
    ("gyroid", "GyroidMode", ["lamella"], True),
    ("body", "Body", None, False),
    ("body", "Body", lambda doc, obj: new(doc, "Part::Plane", "Face"), False),  # not a solid
    ("body", "Body", lambda doc, obj: new(doc, "App::FeaturePython", "Plain"), False),  # no shape at all
    ("body", "Body", lambda doc, obj: new(doc, "Mesh::Feature", "Mesh"), False),
    ("part", "Lattice", None, False),
    ("part", "Lattice", box, False),
    ("part", "Body", lambda doc, obj: new(doc, "Part::Plane", "Face"), False),
    ("part", "Body", lambda doc, obj: new(doc, "App::FeaturePython", "Plain"), False),
    ("part", "Body", lambda doc, obj: obj.Lattice, False),  # 81 solids, not one
    ("part", "Body", lambda doc, obj: obj, True),  # itself
    ("part", "Policy", ["nearest"], True),
    ("part", "Dangling", ["sometimes"], True),
    ("part", "Skin", NAN, True),
    ("part", "Skin", 1e308, True),
    ("part", "Skin", 1e-300, True),
    ("part", "Skin", 40.0, False),  # thicker than the body: only the kernel's offset knows
    ("part", "Density", NAN, True),
    ("mesh", "Lattice", None, False),
    ("mesh", "Lattice", box, False),
    ("mesh", "Lattice", lambda doc, obj: obj, True),
    ("mesh", "Tolerance", 0.0, True),
    ("mesh", "Tolerance", NAN, True),
    ("mesh", "Tolerance", 1e308, True),
    ("mesh", "Tolerance", 5.0, False),  # a quarter of the balls' radius or more: the kernel knows the radii
]


def result(obj):
    """What a failed recompute must keep: the feature's shape or mesh, as a comparable number."""
    return obj.Mesh.CountFacets if hasattr(obj, "Mesh") else obj.Shape.Volume


def put_back(obj, prop, value):
    """A good value again, as a user would set it (an enumeration needs its choices first)."""
    feature_checks.restore(obj, prop, value)


class NonsenseFeaturePropertiesTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("NonsenseFeatures")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def feature(self, kind):
        """A fresh document with a small lattice, a box body and one feature of `kind`, recomputed and valid."""
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = doc = FreeCAD.newDocument("NonsenseFeatures")
        lattice = api.make_lattice(doc, preset="cubic", cells=(2, 2, 2), cell_size=10, node_radius=2.0,
                                   beam_radius=1.0)
        body = doc.addObject("Part::Box", "Box")
        body.Length = body.Width = body.Height = 15.0
        if kind == "stencil":
            obj = api.make_filter(doc, lattice, "stencil", stencil_size=(2, 1, 1), stencil_mask="10")
        elif kind == "coarse":
            coarse = api.make_lattice(doc, preset="cubic", cells=(1, 1, 1), cell_size=20, node_radius=4.0,
                                      beam_radius=2.0)
            obj = api.make_filter(doc, lattice, "lattice-in-lattice", coarse=coarse)
        elif kind == "gyroid":
            obj = api.make_filter(doc, lattice, "gyroid", gyroid_period=10.0, gyroid_thickness=0.5)
        elif kind == "body":
            obj = api.make_filter(doc, lattice, "inside body", body=body)
        elif kind == "part":
            obj = api.make_part(doc, lattice, body)
        else:
            obj = api.make_mesh(doc, lattice, tolerance=0.2)
        doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        return obj

    def test_each_nonsense_value_is_refused_when_set_naming_the_property(self):
        for kind, prop, value, when_set in ROWS:
            if not when_set:
                continue
            with self.subTest(kind=kind, prop=prop, value=value):
                obj = self.feature(kind)
                before, kept = getattr(obj, prop), result(obj)
                with Warnings() as warnings:
                    setattr(obj, prop, value(self.doc, obj) if callable(value) else value)
                self.assertTrue(same(getattr(obj, prop), before), "%s kept %r" % (prop, getattr(obj, prop)))
                self.assertTrue(any(t.startswith("%s: %s" % (obj.Label, prop)) and "keeping" in t
                                    for t in warnings.texts), warnings.texts)
                self.doc.recompute()
                self.assertTrue(obj.isValid(), obj.getStatusString())
                self.assertEqual(result(obj), kept)

    def test_a_nonsense_value_that_got_in_fails_the_recompute_naming_it_then_a_good_one_recomputes(self):
        for kind, prop, value, when_set in ROWS:
            if when_set and prop in feature_checks.LINKS:
                continue  # a cycle: FreeCAD does not recompute the feature at all, so it is refused when set
            with self.subTest(kind=kind, prop=prop, value=value):
                obj = self.feature(kind)
                before, kept = getattr(obj, prop), result(obj)
                obj.Proxy._last_good.clear()  # as after loading a document: no good value to go back to
                with Warnings():
                    setattr(obj, prop, value(self.doc, obj) if callable(value) else value)
                self.doc.recompute()
                self.assertIn("Invalid", obj.State)
                status = obj.getStatusString()
                self.assertTrue(status.startswith("%s: %s: " % (obj.Label, prop)), status)
                self.assertEqual(result(obj), kept)  # nothing lost
                put_back(obj, prop, before)
                self.doc.recompute()
                self.assertTrue(obj.isValid(), obj.getStatusString())
                self.assertEqual(result(obj), kept)


if __name__ == "__main__":
    unittest.main()
