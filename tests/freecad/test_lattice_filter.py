"""LatticeFilter inside FreeCAD: each kind of filter against a numpy brute force, cascades, inversion, bad input,
save and reload."""
import math
import os
import tempfile
import unittest

import numpy as np

import FreeCAD

from brute_force import beams_between, gap_to_lattice
from latticewb import api
from latticewb.kernel import lattice_filter


class LatticeFilterTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("FilterTest")
        self.fine = api.make_lattice(self.doc, preset="cubic", cells=(8, 8, 4), cell_size=2.5, node_radius=0.4,
                                     beam_radius=0.2, representation="Preview")
        self.doc.recompute()
        self.kernel = api.lattice(self.fine)
        self.centers, self.radii = self.kernel.balls()

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def check(self, flt, expected_balls):
        self.doc.recompute()
        self.assertTrue(flt.isValid(), flt.Label)
        filtered = lattice_filter.filtered_lattice(flt)
        balls = filtered.ball_mask()
        self.assertTrue(np.array_equal(balls, expected_balls))
        self.assertTrue(np.array_equal(filtered.beam_mask(), beams_between(self.kernel, expected_balls)))
        self.assertEqual(flt.BallCount, int(expected_balls.sum()))
        return filtered

    def test_stencil(self):
        flt = api.make_filter(self.doc, self.fine, "stencil", stencil_size=(2, 2, 1), stencil_mask="1001")
        ids = np.array([self.kernel.ball_id(q) for q in range(self.kernel.ball_count)])
        expected = (ids[:, 0] % 2) == (ids[:, 1] % 2)  # the mask keeps (0,0) and (1,1) of each 2 x 2 period
        self.check(flt, expected)
        flt.Invert = True
        self.check(flt, ~expected)

    def test_lattice_in_lattice_and_cascade(self):
        coarse = api.make_lattice(self.doc, preset="BCC", cells=(2, 2, 1), cell_size=10.0, node_radius=1.5,
                                  beam_radius=0.8)
        self.doc.recompute()
        lil = api.make_filter(self.doc, self.fine, "lattice-in-lattice", coarse=coarse)
        # a fine ball is kept when it meets the coarse lattice: gap from its centre to the coarse <= its radius
        expected = gap_to_lattice(self.centers, api.lattice(coarse)) <= self.radii + 1e-12
        self.assertGreater(expected.sum(), 10)
        self.check(lil, expected)
        # a cascade: inside a cylinder too
        body = self.doc.addObject("Part::Cylinder", "Cylinder")
        body.Radius, body.Height = 8.0, 20.0
        body.Placement.Base = FreeCAD.Vector(10, 10, -5)
        inside = api.make_filter(self.doc, lil, "inside body", body=body)
        in_cylinder = np.hypot(self.centers[:, 0] - 10, self.centers[:, 1] - 10) <= 8.0
        self.check(inside, expected & in_cylinder)

    def test_gyroid(self):
        flt = api.make_filter(self.doc, self.fine, "gyroid", gyroid_period=10.0, gyroid_thickness=0.5)
        x, y, z = (2 * math.pi * self.centers / 10.0).T
        g = np.sin(x) * np.cos(y) + np.sin(y) * np.cos(z) + np.sin(z) * np.cos(x)
        self.check(flt, np.abs(g) <= 0.5)
        flt.GyroidMode = "solid"
        self.check(flt, g <= 0.5)

    def test_a_body_of_several_solids_is_their_union(self):
        """Issue 16: a compound (or compsolid) of several solids keeps the nodes inside any of them, checked against
        FreeCAD's own isInside per solid; a face beside the solids is refused, naming Body."""
        import Part
        V = FreeCAD.Vector
        a, b = Part.makeBox(6, 6, 6, V(-1, -1, -1)), Part.makeBox(6, 6, 6, V(3, 3, -1))
        apart, beside = Part.makeBox(5, 5, 6, V(10, 10, -1)), Part.makeBox(6, 6, 6, V(5, -1, -1))
        points = [FreeCAD.Vector(*p) for p in self.centers]
        for name, shape in [("Apart", Part.makeCompound([a, apart])), ("Overlapping", Part.makeCompound([a, b])),
                            ("CompSolid", Part.CompSolid([a, beside]))]:
            holder = self.doc.addObject("Part::Feature", name)
            holder.Shape = shape
            flt = api.make_filter(self.doc, self.fine, "inside body", body=holder)
            inside = [np.array([s.isInside(p, 1e-7, True) for p in points]) for s in shape.Solids]
            expected = np.logical_or.reduce(inside)
            # each solid holds nodes the other does not: neither the first solid alone nor an exclusive or passes
            self.assertTrue((inside[0] & ~inside[1]).any() and (inside[1] & ~inside[0]).any(), name)
            self.check(flt, expected)
        holder = self.doc.addObject("Part::Feature", "WithAFace")
        holder.Shape = Part.makeCompound([a, Part.makePlane(5, 5, V(10, 10, 0))])
        flt = api.make_filter(self.doc, self.fine, "inside body", body=holder)
        self.doc.recompute()
        self.assertIn("Invalid", flt.State)
        self.assertIn("Body: WithAFace holds 1 faces outside its solids", flt.getStatusString())
        # the kernel refuses the same body given directly
        import steadylattice as sl
        with self.assertRaisesRegex(ValueError, "^body: holds 1 faces outside its solids"):
            sl.InsideBody(holder.Shape.exportBrepToString())

    def test_bad_input_and_reload(self):
        flt = api.make_filter(self.doc, self.fine, "stencil", stencil_size=(2, 1, 1), stencil_mask="10")
        self.doc.recompute()
        kept = flt.BallCount
        flt.StencilMask = "101"  # wrong length for a 2 x 1 x 1 period
        self.doc.recompute()
        self.assertIn("Invalid", flt.State)
        flt.StencilMask = "10"
        flt.Kind = "lattice-in-lattice"  # no coarse lattice linked
        self.doc.recompute()
        self.assertIn("Invalid", flt.State)
        flt.Kind = "stencil"
        self.doc.recompute()
        self.assertTrue(flt.isValid())
        with self.assertRaises(ValueError):
            api.make_filter(self.doc, self.fine, "voronoi")
        with self.assertRaises(ValueError):
            api.make_filter(self.doc, self.fine, "stencil", mask="1")
        path = os.path.join(tempfile.mkdtemp(), "filter.FCStd")
        name = flt.Name
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        again = self.doc.getObject(name)
        again.touch()
        self.doc.recompute()
        self.assertEqual(again.BallCount, kept)
