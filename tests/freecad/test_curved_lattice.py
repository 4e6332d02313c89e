"""CurvedLattice inside FreeCAD (issue 15): a BeCOTS lattice from four corners typed or linked to vertices, rebuilt
when a corner is edited or a linked vertex moves, bad corners and nonsense properties refused naming the property,
and a LatticePart trimming it into a cylinder with the 'bridge' policy (one valid solid, every hub that lost a
neighbour bridged, the part's volume the kernel's, its STL bridged too)."""
import math
import os
import tempfile
import unittest

import numpy as np

import FreeCAD

import steadylattice as sl
from latticewb import api
from latticewb.kernel import curved_lattice, mesh_export
from property_editing import Warnings, same

# A planar sector of rings about the z axis in the plane z = 1: radius 7 to 24, 160 degrees (corners can turn by at
# most half a turn: the map takes the principal angle).
TURN = math.radians(160.0)


def ring_point(radius, angle, z=1.0):
    return FreeCAD.Vector(radius * math.cos(angle), radius * math.sin(angle), z)


CORNERS = [ring_point(7, 0), ring_point(24, 0), ring_point(24, TURN), ring_point(7, TURN)]


def close(a, b, tol=1e-9):
    return (FreeCAD.Vector(*a) - FreeCAD.Vector(*b)).Length < tol


class CurvedLatticeTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("CurvedLatticeTest")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def make(self, **params):
        args = dict(corners=CORNERS, cells=(8, 6), layers=2, layer_raise=2.5, node_radius=0.35, beam_ratio=0.5)
        args.update(params)
        obj = api.make_curved_lattice(self.doc, **args)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        return obj

    def corners_of_map(self, obj):
        return curved_lattice.becots_map(obj).map(np.array([[0, 0], [0, 1], [1, 1], [1, 0]], dtype=float))

    def test_builds_and_follows_an_edited_corner(self):
        obj = self.make()
        self.assertEqual(obj.BallCount, 8 * 6 * 2)  # triangle: one node per group
        self.assertGreater(obj.BeamCount, obj.BallCount)
        self.assertTrue(obj.Shape.Solids)  # Auto: balls and beams as solids at this size
        for got, want in zip(self.corners_of_map(obj), CORNERS):
            self.assertTrue(close(got, want), (got, want))
        centers, radii = curved_lattice.lattice(obj).balls()
        self.assertTrue(close(centers[0], CORNERS[0]))
        self.assertAlmostEqual(radii[0], 0.35)
        before = obj.Shape.BoundBox
        obj.C = CORNERS[2] + FreeCAD.Vector(0, 0, 4)  # lifted: the sheet rolls onto a cone
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertTrue(close(self.corners_of_map(obj)[2], obj.C))
        self.assertFalse(curved_lattice.becots_map(obj).is_flat)
        self.assertGreater(obj.Shape.BoundBox.ZMax, before.ZMax + 1.0)

    def test_saved_and_reopened_with_its_links(self):
        vertex = self.doc.addObject("Part::Vertex", "Corner")
        vertex.X, vertex.Y, vertex.Z = CORNERS[1].x, CORNERS[1].y, CORNERS[1].z
        self.doc.recompute()
        obj = self.make(connectivity="kagome", links=[None, (vertex, ""), None, None])
        balls, beams, name = obj.BallCount, obj.BeamCount, obj.Name
        path = os.path.join(tempfile.mkdtemp(), "curved.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        obj = self.doc.getObject(name)
        self.assertEqual(obj.BLink[0].Name, "Corner")
        obj.touch()
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual((obj.BallCount, obj.BeamCount), (balls, beams))
        self.assertEqual(obj.Connectivity, "kagome")
        self.assertTrue(close(self.corners_of_map(obj)[1], CORNERS[1]))

    def test_corners_from_linked_vertices_follow_them(self):
        vertices = []
        for k, p in enumerate(CORNERS):
            v = self.doc.addObject("Part::Vertex", "V%d" % k)
            v.X, v.Y, v.Z = p.x, p.y, p.z
            vertices.append(v)
        self.doc.recompute()
        obj = self.make(corners=None, links=[(v, "") for v in vertices[:3]] + [(vertices[3], "Vertex1")])
        for got, want in zip(self.corners_of_map(obj), CORNERS):
            self.assertTrue(close(got, want), (got, want))
        vertices[1].Z = 6.0  # B moves: the lattice follows on recompute
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertTrue(close(self.corners_of_map(obj)[1], (24, 0, 6)))
        # a link to a shape of several vertices, with none picked, fails naming the link
        box = self.doc.addObject("Part::Box", "Box")
        obj.ALink = (box, [])
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertTrue(obj.getStatusString().startswith("%s: ALink: " % obj.Label), obj.getStatusString())
        obj.ALink = (box, ["Vertex1"])
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertTrue(close(self.corners_of_map(obj)[0], box.Shape.Vertexes[0].Point))
        # a sketch's point (a sketch's Shape does not hold lone points: taken from its geometry and placement)
        import Part
        sketch = self.doc.addObject("Sketcher::SketchObject", "Sketch")
        sketch.addGeometry(Part.LineSegment(FreeCAD.Vector(-3, -3, 0), FreeCAD.Vector(-2, -3, 0)))
        sketch.addGeometry(Part.Point(FreeCAD.Vector(CORNERS[0].x, CORNERS[0].y, 0)))
        sketch.Placement.Base = FreeCAD.Vector(0, 0, 1)
        self.doc.recompute()
        obj.ALink = (sketch, ["Vertex3"])  # the line's two ends come first
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertTrue(close(self.corners_of_map(obj)[0], CORNERS[0]))
        sketch.Placement.Base = FreeCAD.Vector(0, 0, 2)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertTrue(close(self.corners_of_map(obj)[0], CORNERS[0] + FreeCAD.Vector(0, 0, 1)))
        obj.ALink = (sketch, ["Vertex9"])
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertIn("ALink: Sketch has no Vertex9", obj.getStatusString())

    def test_bad_corners_fail_naming_them(self):
        obj = self.make()
        kept = obj.BallCount
        obj.D = CORNERS[0]  # coincides with A
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        status = obj.getStatusString()
        self.assertTrue(status.startswith(obj.Label + ": "), status)
        self.assertIn("corners A, D", status)
        self.assertEqual(obj.BallCount, kept)
        obj.D = CORNERS[3]
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())

    def test_nonsense_properties_are_refused_naming_them(self):
        obj = self.make()
        for prop, value in [("BeamRatio", 2.0), ("BeamRatio", float("nan")), ("NodeRadius", 0.0),
                            ("Connectivity", ["hexagon"]), ("LayerRaise", float("inf")),
                            ("A", FreeCAD.Vector(float("nan"), 0, 0))]:
            with self.subTest(prop=prop, value=value):
                before = getattr(obj, prop)
                with Warnings() as warnings:
                    setattr(obj, prop, value)
                self.assertTrue(same(getattr(obj, prop), before), (prop, getattr(obj, prop)))
                self.assertTrue(any(t.startswith("%s: %s" % (obj.Label, prop)) for t in warnings.texts),
                                warnings.texts)
        with self.assertRaises(ValueError) as raised:
            api.make_curved_lattice(self.doc, connectivity="square")
        self.assertIn("connectivity", str(raised.exception))

    def test_trimmed_into_a_cylinder_with_bridges(self):
        lattice = self.make()
        body = self.doc.addObject("Part::Cylinder", "Body")
        body.Radius, body.Height = 20.0, 22.0
        body.Placement.Base = FreeCAD.Vector(0, 0, -1)
        part = api.make_part(self.doc, lattice, body, policy="bridge")
        self.doc.recompute()
        self.assertTrue(part.isValid(), part.getStatusString())
        self.assertTrue(part.Shape.isValid())
        self.assertEqual(len(part.Shape.Solids), 1)
        stats = {}
        text = curved_lattice.lattice(lattice).brep(body.Shape.exportBrepToString(), "bridge", stats=stats)
        self.assertGreater(stats["bridges"], 0)
        self.assertEqual(stats["bridges"], stats["lost_neighbour_hubs"])
        self.assertEqual(stats["blocked_bridges"], 0)
        self.assertAlmostEqual(part.Volume, sl.brep_properties(text)["volume"], delta=1e-9 * part.Volume)
        # whole keeps the same hubs without bridges: less material
        whole = sl.brep_properties(curved_lattice.lattice(lattice).brep(body.Shape.exportBrepToString(), "whole",
                                                                         dangling="remove"))
        self.assertLess(whole["volume"], part.Volume)
        # the part's mesh bridges too (the kernel's trimmed mesh of the bridged lattice); a 3MF beam lattice,
        # which the printer clips, is refused naming the policy rather than clipped silently
        folder = tempfile.mkdtemp()
        mesh_stats = mesh_export.write_mesh_file(part, os.path.join(folder, "part.stl"), ".stl", tolerance=0.02)
        self.assertEqual(mesh_stats["bridges"], stats["bridges"])
        self.assertGreater(os.path.getsize(os.path.join(folder, "part.stl")), 84)
        with self.assertRaises(ValueError) as raised:
            mesh_export.write_mesh_file(part, os.path.join(folder, "part.3mf"), ".3mf")
        self.assertTrue(str(raised.exception).startswith("Policy: "), str(raised.exception))
        self.assertIn("'bridge'", str(raised.exception))
        # the corner edit re-trims the part
        lattice.B = CORNERS[1] * (22.0 / 24.0) + FreeCAD.Vector(0, 0, 1.0 * (1 - 22.0 / 24.0))
        self.doc.recompute()
        self.assertTrue(part.isValid(), part.getStatusString())
        self.assertEqual(len(part.Shape.Solids), 1)


if __name__ == "__main__":
    unittest.main()
