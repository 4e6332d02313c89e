"""SteadyLattice layouts in a designer's terms: grading (taper, twist, bend) checked against independent geometry,
frames, switching layouts without a jump, and the preview representation."""
import math
import os
import tempfile
import unittest

import numpy as np

import FreeCAD
import Part

from latticewb import api


class LayoutTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("LayoutTest")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def balls(self, obj):
        return api.lattice(obj).balls()

    def test_bend_puts_rows_on_circles(self):
        # rows along U bend toward V by 9 degrees per 10 mm cell: the centre row lies on a circle of radius
        # 10 / (9 degrees in radians) around a centre beside the row, in the UV plane
        obj = api.make_lattice(self.doc, preset="cubic", cells=(6, 2, 2), cell_size=10.0, node_radius=1.0,
                               bend_u=9.0, bend_u_toward="V")
        self.doc.recompute()
        lat = api.lattice(obj)
        self.assertEqual(obj.AppliedOrder, "VWU")  # the bent direction applies last
        centers, _ = lat.balls()
        theta = math.radians(9.0)
        radius = 10.0 / theta
        centre = np.array([0.0, 10.0 + radius, 10.0])
        row = np.array([centers[api.ball_index_of(obj, lat, i, 1, 1, 0)] for i in range(7)])
        # every row along U bends about the same axis: concentric arcs
        outer = np.array([centers[api.ball_index_of(obj, lat, i, 2, 1, 0)] for i in range(7)])
        self.assertLess(np.abs(np.linalg.norm(outer - centre, axis=1) - (radius - 10.0)).max(), 1e-9)
        self.assertLess(np.abs(np.linalg.norm(row - centre, axis=1) - radius).max(), 1e-9)
        angles = np.unwrap(np.arctan2(row[:, 0] - centre[0], -(row[:, 1] - centre[1])))
        self.assertLess(np.abs(np.diff(angles) - theta).max(), 1e-12)
        self.assertLess(np.abs(row[:, 2] - 10.0).max(), 1e-12)  # stays in its plane

    def test_twist_and_taper_about_the_centre_line(self):
        obj = api.make_lattice(self.doc, preset="cubic", cells=(2, 2, 4), cell_size=10.0, node_radius=1.0,
                               twist_w=7.0, taper_w=-4.0)
        self.doc.recompute()
        lat = api.lattice(obj)
        axis = np.array([10.0, 10.0])  # the centre line along W
        base = np.array(lat.ball(2, 0, 0, 0)[0])
        for k in range(5):
            p, r = lat.ball(2, 0, k, 0)
            self.assertAlmostEqual(r, 1.0 * 0.96 ** k, places=12)
            # distance to the centre line scales by the taper; the angle about it turns by the twist
            d0, dk = base[:2] - axis, np.array(p[:2]) - axis
            self.assertAlmostEqual(np.linalg.norm(dk), 0.96 ** k * np.linalg.norm(d0), places=9)
            turned = math.degrees(math.atan2(dk[1], dk[0]) - math.atan2(d0[1], d0[0]))
            self.assertAlmostEqual((turned - 7.0 * k + 180) % 360 - 180, 0.0, places=9)
        # the centre line itself keeps its place: a ball on it only moves along W
        on_axis = api.make_lattice(self.doc, preset="cubic", cells=(2, 2, 4), cell_size=10.0, twist_w=7.0)
        self.doc.recompute()
        p = api.lattice(on_axis).ball(1, 1, 3, 0)[0]
        self.assertLess(np.abs(np.array(p) - (10, 10, 30)).max(), 1e-9)

    def test_no_grading_is_the_regular_lattice(self):
        obj = api.make_lattice(self.doc, preset="BCC", cells=(3, 2, 2), cell_size=5.0)
        self.doc.recompute()
        centers, _ = self.balls(obj)
        lat = api.lattice(obj)
        for index in range(lat.ball_count):
            i, j, k, n = lat.ball_id(index)
            expected = np.array([i, j, k]) * 5.0 + (2.5 if n == 1 else 0.0)
            self.assertLess(np.abs(centers[index] - expected).max(), 1e-12)

    def test_frames_put_the_last_cells_where_asked(self):
        end_u = FreeCAD.Placement(FreeCAD.Vector(40, 5, 0), FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), 30))
        obj = api.make_lattice(self.doc, preset="cubic", cells=(4, 2, 2), cell_size=10.0, node_radius=1.0,
                               layout="frames", end_u=end_u, end_scale_u=0.5,
                               end_v=FreeCAD.Placement(FreeCAD.Vector(0, 20, 0), FreeCAD.Rotation()),
                               end_w=FreeCAD.Placement(FreeCAD.Vector(0, 0, 20), FreeCAD.Rotation()))
        self.doc.recompute()
        lat = api.lattice(obj)
        p, r = lat.ball(4, 0, 0, 0)
        self.assertLess(np.abs(np.array(p) - (40, 5, 0)).max(), 1e-9)
        self.assertAlmostEqual(r, 0.5, places=12)
        p, r = lat.ball(0, 2, 0, 0)
        self.assertLess(np.abs(np.array(p) - (0, 20, 0)).max(), 1e-9)

    def test_switching_layouts_keeps_the_lattice(self):
        obj = api.make_lattice(self.doc, preset="octet", cells=(3, 2, 2), cell_size=8.0, node_radius=1.0,
                               beam_radius=0.6, taper_u=3.0, twist_w=5.0, bend_v=4.0, bend_v_toward="W")
        self.doc.recompute()
        reference, _ = self.balls(obj)
        for layout in ("steps", "frames"):
            obj.Layout = layout
            self.doc.recompute()
            centers, _ = self.balls(obj)
            self.assertLess(np.abs(centers - reference).max(), 1e-8, layout)

    def test_preview_representation(self):
        obj = api.make_lattice(self.doc, preset="octet", cells=(12, 12, 12), cell_size=5.0, node_radius=0.8,
                               beam_radius=0.5)
        self.doc.recompute()
        self.assertGreater(obj.BeamCount, 5000)
        self.assertEqual(len(obj.Shape.Solids), 0)  # Auto: too many for solids, previewed
        small = api.make_lattice(self.doc, preset="cubic", cells=(2, 1, 1), representation="Preview")
        self.doc.recompute()
        self.assertEqual(len(small.Shape.Solids), 0)
        path = api.export([small], os.path.join(tempfile.mkdtemp(), "small.step"))
        self.assertEqual(len(Part.read(path).Solids), small.BallCount + small.BeamCount)
        small.Representation = "Elements"
        self.doc.recompute()
        self.assertEqual(len(small.Shape.Solids), small.BallCount + small.BeamCount)


if __name__ == "__main__":
    unittest.main()


class SolidRepresentationTest(unittest.TestCase):
    def test_solid_is_one_exact_brep(self):
        doc = FreeCAD.newDocument("SolidTest")
        try:
            obj = api.make_lattice(doc, preset="octet", cells=(2, 2, 2), cell_size=8.0, node_radius=1.3,
                                   beam_radius=0.55, twist_w=5.0, representation="Solid")
            obj.Placement.Base = FreeCAD.Vector(100, 0, 0)
            doc.recompute()
            self.assertTrue(obj.isValid())
            self.assertEqual(len(obj.Shape.Solids), 1)
            self.assertTrue(obj.Shape.isValid())
            # the closed-form volume of the same lattice, computed independently of the B-rep
            self.assertAlmostEqual(obj.Shape.Volume, api.properties(obj)["volume"], delta=1e-6 * obj.Shape.Volume)
            self.assertGreater(obj.Shape.BoundBox.XMin, 90.0)  # placed by the object's Placement
        finally:
            FreeCAD.closeDocument(doc.Name)
