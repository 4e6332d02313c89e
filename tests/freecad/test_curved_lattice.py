"""CurvedLattice inside FreeCAD (issue 15): a BeCOTS lattice from four corners typed or linked to vertices, rebuilt
when a corner is edited or a linked vertex moves, bad corners and nonsense properties refused naming the property,
and a LatticePart trimming it into a cylinder with the 'bridge' policy (one valid solid, every hub that lost a
neighbour bridged, the part's volume the kernel's, its STL bridged too); rings from TurnsU: three quarters of a turn
on a cone, a whole ring closed seamlessly (no repeated balls, the seam joined), a sheet winding over itself refused,
both trimmed into a body."""
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

# A planar sector of rings about the z axis in the plane z = 1: radius 7 to 24, 160 degrees (corners alone turn by
# at most half a turn: the map takes the principal angle; TurnsU adds whole turns).
TURN = math.radians(160.0)


def ring_point(radius, angle, z=1.0):
    return FreeCAD.Vector(radius * math.cos(angle), radius * math.sin(angle), z)


CORNERS = [ring_point(7, 0), ring_point(24, 0), ring_point(24, TURN), ring_point(7, TURN)]


# A cone about the z axis, apex (0, 0, -10): U turns a quarter turn with no growth, V grows by 1.4 and twists by 20
# degrees (so the corners are not coplanar).
APEX = FreeCAD.Vector(0, 0, -10)


def cone_point(p, angle, scale=1.0):
    rot = FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), math.degrees(angle))
    return APEX + rot.multVec(p - APEX) * scale


def cone_corners(turn):
    a = FreeCAD.Vector(8, 0, 0)
    b = cone_point(a, math.radians(20), 1.4)
    return [a, b, cone_point(b, turn), cone_point(a, turn)]


def angles_about_z(points):
    """Angles (degrees) of points about the z axis, unwrapped along the sequence."""
    return np.degrees(np.unwrap(np.arctan2(points[:, 1], points[:, 0])))


def min_distance(centers):
    d = np.linalg.norm(centers[:, None, :] - centers[None, :, :], axis=2)
    np.fill_diagonal(d, np.inf)
    return d.min()


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

    def test_layers_offset_along_the_normal(self):
        # 6.3 (b): each layer's corner A moved by LayerOffset along the sheet's normal at A; the layer is the
        # field's map through that corner (the kernel's BecotsMap.from_field, independently of the object).
        import steadylattice as sl
        lifted = [CORNERS[0], CORNERS[1], CORNERS[2] + FreeCAD.Vector(0, 0, 4), CORNERS[3]]
        obj = self.make(corners=lifted, layers=3, layer_raise=0.0, layer_offset=1.5)
        field = curved_lattice.becots_map(obj)
        normal = np.asarray(field.normal)
        tangent_u = field.map((1e-6, 0.0)) - field.map((-1e-6, 0.0))
        tangent_v = field.map((0.0, 1e-6)) - field.map((0.0, -1e-6))
        self.assertLess(abs(np.dot(normal, tangent_u / np.linalg.norm(tangent_u))), 1e-6)
        self.assertLess(abs(np.dot(normal, tangent_v / np.linalg.norm(tangent_v))), 1e-6)
        lat = curved_lattice.lattice(obj)
        centers, _ = lat.balls()
        for k in range(3):
            a_k = np.asarray(lifted[0]) + 1.5 * k * normal
            layer = sl.BecotsMap.from_field(field.apex, field.axis, a_k, field.log_u, field.log_v)
            for i, j in [(0, 0), (7, 0), (3, 5), (7, 5)]:
                self.assertTrue(close(centers[lat.ball_index(i, j, k, 0)], layer.map((i / 8, j / 6))), (i, j, k))
        self.assertEqual(lat.query_plan()["automatic"], "becots")
        self.assertEqual(obj.BallCount, 8 * 6 * 3)
        obj.LayerOffset = -1.0
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertTrue(close(curved_lattice.lattice(obj).balls()[0][lat.ball_index(0, 0, 2, 0)],
                              np.asarray(lifted[0]) - 2.0 * normal))

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
                            ("LayerOffset", float("nan")),
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


    def trim_into_cylinder(self, lattice, radius):
        body = self.doc.addObject("Part::Cylinder", "Body")
        body.Radius, body.Height = radius, 40.0
        body.Placement.Base = APEX
        part = api.make_part(self.doc, lattice, body, policy="bridge")
        self.doc.recompute()
        self.assertTrue(part.isValid(), part.getStatusString())
        self.assertTrue(part.Shape.isValid())
        self.assertEqual(len(part.Shape.Solids), 1)
        self.assertGreater(part.Volume, 0.0)
        stats = {}
        curved_lattice.lattice(lattice).brep(body.Shape.exportBrepToString(), "bridge", stats=stats)
        self.assertGreater(stats["bridges"], 0)
        self.assertEqual(stats["bridges"], stats["lost_neighbour_hubs"])
        return part

    def test_three_quarters_of_a_turn_from_turns_u(self):
        corners = cone_corners(math.radians(90))
        obj = self.make(corners=corners, cells=(9, 3), layers=1, turns=(-1, 0), node_radius=0.3)
        lat = curved_lattice.lattice(obj)
        self.assertEqual(lat.counts, (9, 3, 1))  # no group falls on the first: nothing left out
        # the kernel's map with the branch that turns U three quarters (the other way round from the corners)
        a, b, c, d = (tuple(p) for p in corners)
        maps = [sl.BecotsMap(a, b, c, d, branches=(k, 0)) for k in (-1, 1)]
        wanted = [m for m in maps if abs(abs(m.log_u.imag) - 1.5 * math.pi) < 1e-9]
        self.assertEqual(len(wanted), 1)
        self.assertAlmostEqual(abs(curved_lattice.becots_map(obj).log_u.imag), 1.5 * math.pi, delta=1e-9)
        for i in range(9):
            for j in range(3):
                center, radius = lat.ball(i, j, 0, 0)
                self.assertTrue(close(center, wanted[0].map((i / 9.0, j / 3.0)), 1e-9), (i, j))
        # about the cone's axis (z through the apex): the corners turn +90 degrees; -1 goes the other way round,
        # 30 degrees a column, and the first row spans 8 of 9 columns of 270 degrees: more than a half turn
        row = angles_about_z(np.array([lat.ball(i, 0, 0, 0)[0] for i in range(9)]))
        np.testing.assert_allclose(np.diff(row), -30.0, atol=1e-7)
        self.assertGreater(abs(row[-1] - row[0]), 180.0)
        # TurnsU 1 goes on the way the corners turn instead: 450 degrees, 50 a column; on this cone (no growth
        # along U) the ninth column then crosses the first two: refused naming TurnsU rather than overlapping
        obj.TurnsU = 1
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertIn("TurnsU: the sheet winds over itself (U turns 450.0", obj.getStatusString())
        row = angles_about_z(curved_lattice.becots_map(obj).map(np.array([[i / 9.0, 0.0] for i in range(9)])))
        np.testing.assert_allclose(np.diff(row), 50.0, atol=1e-7)
        obj.TurnsU = -1
        self.doc.recompute()
        self.assertTrue(obj.Shape.isValid())
        self.assertEqual(len(obj.Shape.Solids), obj.BallCount + obj.BeamCount)  # the preview: element solids
        self.trim_into_cylinder(obj, 10.5)

    def test_a_whole_ring_is_closed_without_repeated_balls(self):
        # D an eighth of a turn from A, one more turn: 9 cells of 45 degrees, the 9th group falls on the first
        obj = self.make(corners=cone_corners(math.radians(45)), cells=(9, 3), layers=1, turns=(1, 0),
                        node_radius=0.3)
        lat, ring = curved_lattice.lattice_and_ring(obj)
        self.assertEqual(ring, (0, 8, 9))
        self.assertEqual(lat.counts, (8, 3, 1))
        self.assertEqual(obj.BallCount, 8 * 3)
        # the lattice as asked for holds the repeated column: its balls coincide with the first column's
        repeated = sl.becots_lattice(curved_lattice.becots_map(obj), "triangle", (9, 3, 1), 0.3, beam_ratio=0.5)
        self.assertLess(min_distance(repeated.balls()[0]), 1e-9)
        centers, radii = lat.balls()
        self.assertGreater(min_distance(centers), 2.0 * radii.max())  # no two balls closer than a ball's width
        # the seam is joined: triangle beams along U close the loop (8 per row), V and diagonals as usual
        self.assertEqual(obj.BeamCount, 8 * 3 + 8 * 2 + 8 * 2)
        start, end = lat.beams()[:2]
        pairs = {frozenset(p) for p in zip(start.tolist(), end.tolist())}
        for j in range(3):
            self.assertIn(frozenset((lat.ball_index(7, j, 0, 0), lat.ball_index(0, j, 0, 0))), pairs)
        # no element meets a foreign one (crowded exit circles on a ball are built as they are without turns)
        self.assertEqual({i["kind"] for i in lat.clean_check()["issues"]} - {"circle_overlap"}, set())
        self.assertTrue(obj.Shape.isValid())
        self.assertEqual(len(obj.Shape.Solids), obj.BallCount + obj.BeamCount)
        # the whole ring as one solid: FreeCAD reads the kernel's B-rep, its volume the kernel's closed form
        import Part
        shape = Part.Shape()
        shape.importBrepFromString(lat.brep())
        self.assertTrue(shape.isValid())
        self.assertEqual(len(shape.Solids), 1)
        self.assertAlmostEqual(shape.Volume, lat.properties()["volume"], delta=1e-7 * shape.Volume)
        self.trim_into_cylinder(obj, 10.5)
        # the same ring along V (the corners taken with U and V swapped): closed after 8 rows just as well
        a, b, c, d = cone_corners(math.radians(45))
        along_v = self.make(corners=[a, d, c, b], cells=(3, 9), layers=1, turns=(0, 1), node_radius=0.3)
        lat_v, ring_v = curved_lattice.lattice_and_ring(along_v)
        self.assertEqual((ring_v, lat_v.counts, along_v.BeamCount), ((1, 8, 9), (3, 8, 1), obj.BeamCount))
        self.assertGreater(min_distance(lat_v.balls()[0]), 2.0 * radii.max())
        # ten cells of 40.5 degrees: no group falls on the first, the tenth overlaps it: refused naming TurnsU
        obj.CellsU = 10
        self.doc.recompute()
        self.assertIn("Invalid", obj.State)
        self.assertIn("TurnsU: the sheet winds over itself", obj.getStatusString())
        self.assertIn("meet", obj.getStatusString())

    def test_turns_refused_beyond_the_kernel_limit_and_saved(self):
        obj = self.make(corners=cone_corners(math.radians(45)), cells=(9, 3), layers=1, turns=(1, 0),
                        node_radius=0.3)
        a, b, c, d = (tuple(p) for p in cone_corners(math.radians(45)))
        sl.BecotsMap(a, b, c, d, branches=(curved_lattice.MAX_TURNS, 0))  # the kernel's own limit
        with self.assertRaises(ValueError):
            sl.BecotsMap(a, b, c, d, branches=(curved_lattice.MAX_TURNS + 1, 0))
        for prop in ("TurnsU", "TurnsV"):
            with self.subTest(prop=prop):
                before = getattr(obj, prop)
                with Warnings() as warnings:
                    setattr(obj, prop, curved_lattice.MAX_TURNS + 1)
                self.assertEqual(getattr(obj, prop), before)
                self.assertTrue(any(t.startswith("%s: %s: must be within" % (obj.Label, prop)) for t in warnings.texts),
                                warnings.texts)
        # a parallelogram's U and V are translations, which have no turns: the recompute fails naming TurnsU
        flat = api.make_curved_lattice(self.doc, corners=[(0, 0, 0), (0, 10, 0), (10, 10, 0), (10, 0, 0)],
                                       turns=(1, 0))
        self.doc.recompute()
        self.assertIn("Invalid", flat.State)
        self.assertTrue(flat.getStatusString().startswith(flat.Label + ": TurnsU: "), flat.getStatusString())
        self.doc.removeObject(flat.Name)
        with self.assertRaises(ValueError) as raised:
            api.make_curved_lattice(self.doc, turns=(1, 0.5))
        self.assertIn("turns", str(raised.exception))
        # saved and reopened as a ring; a document saved before the turns existed opens with none
        old = self.make(name="Old")
        old.removeProperty("TurnsU")
        old.removeProperty("TurnsV")
        old_balls, name = old.BallCount, obj.Name
        path = os.path.join(tempfile.mkdtemp(), "ring.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        obj, old = self.doc.getObject(name), self.doc.getObject("Old")
        self.assertEqual((obj.TurnsU, obj.TurnsV), (1, 0))
        self.assertEqual((old.TurnsU, old.TurnsV), (0, 0))
        for o in (obj, old):
            o.touch()
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertTrue(old.isValid(), old.getStatusString())
        self.assertEqual(curved_lattice.lattice(obj).counts, (8, 3, 1))
        self.assertEqual(old.BallCount, old_balls)


if __name__ == "__main__":
    unittest.main()


class FaceLatticeTest(unittest.TestCase):
    """A CurvedLattice laid on a planar, cylindrical or conical face: the corners projected onto it, the field
    following its surface, the layers going into the body (checked against the face's geometry and the kernel's
    map through each moved corner, not against the object's own code)."""

    def setUp(self):
        self.doc = FreeCAD.newDocument("FaceLatticeTest")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def laid(self, face, corners, **params):
        args = dict(connectivity="triangle", cells=(6, 5), layers=3, layer_offset=2.5, node_radius=0.8,
                    beam_ratio=0.5)
        args.update(params)
        obj = api.make_curved_lattice(self.doc, corners=corners, face=face, **args)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        return obj, curved_lattice.lattice(obj)

    def test_a_ring_around_a_cylinder_in_layers_inward_bridged_into_it(self):
        body = self.doc.addObject("Part::Cylinder", "Body")
        body.Radius, body.Height = 20.0, 40.0
        self.doc.recompute()
        eighth = math.pi / 4
        # corners off the face (radius 23): projected onto it; D an eighth of a turn on, TurnsU closes the ring
        corners = [FreeCAD.Vector(23, 0, 6), FreeCAD.Vector(23, 0, 34), FreeCAD.Vector(0, 0, 0),
                   FreeCAD.Vector(23 * math.cos(eighth), 23 * math.sin(eighth), 6)]
        obj, lat = self.laid((body, "Face1"), corners, cells=(9, 4), turns=(1, 0), layer_offset=3.0)
        self.assertEqual(lat.counts, (8, 4, 3))  # the ninth column would repeat the first: a closed ring
        centers, radii = lat.balls()
        self.assertLess(np.abs(radii - 0.8).max(), 1e-12)  # no dilation on a cylinder
        for k in range(3):
            at = [lat.ball_index(i, j, k, 0) for i in range(8) for j in range(4)]
            distance = np.hypot(centers[at, 0], centers[at, 1])
            self.assertLess(np.abs(distance - (20.0 - 3.0 * k)).max(), 1e-9, k)  # layer k, 3k inward
            angles = sorted(np.arctan2(centers[at, 1], centers[at, 0]) % (2 * math.pi))
            self.assertAlmostEqual(angles[-1] - angles[0], 7 * eighth, places=9)
        self.assertTrue(close(centers[lat.ball_index(0, 0, 0, 0)], (20, 0, 6)))
        self.assertTrue(close(centers[lat.ball_index(0, 3, 0, 0)], (20, 0, 6 + 28 * 3 / 4)))
        part = api.make_part(self.doc, obj, body, policy="bridge")
        self.doc.recompute()
        self.assertTrue(part.isValid(), part.getStatusString())
        self.assertTrue(part.Shape.isValid())
        self.assertEqual(len(part.Shape.Solids), 1)
        stats = {}
        lat.brep(body.Shape.exportBrepToString(), "bridge", stats=stats)
        self.assertGreater(stats["bridges"], 0)
        self.assertEqual(stats["bridges"], stats["lost_neighbour_hubs"])

    def test_a_cone_face_gives_its_own_field(self):
        body = self.doc.addObject("Part::Cone", "Body")
        body.Radius1, body.Radius2, body.Height = 22.0, 8.0, 28.0
        self.doc.recompute()
        face = body.Shape.Faces[0]
        self.assertEqual(type(face.Surface).__name__, "Cone")
        corners = [FreeCAD.Vector(25, 0, 4), FreeCAD.Vector(14, 0, 22), FreeCAD.Vector(5, 5, 5),
                   FreeCAD.Vector(19 * math.cos(1.0), 19 * math.sin(1.0), 4)]
        obj, lat = self.laid((body, "Face1"), corners, layer_offset=1.5)
        self.assertEqual(lat.query_plan()["automatic"], "becots")
        field = curved_lattice.face_field.lay_on_face(obj, face, "Body.Face1", corner_points_of(obj),
                                                      "triangle", (0, 0), None)[0]
        apex, axis = face.Surface.Apex, face.Surface.Axis
        self.assertLess(np.abs(np.asarray(field.apex) - tuple(apex)).max(), 1e-9)  # the face's apex, not another
        centers, radii = lat.balls()
        for x in (lat.ball_index(i, j, 0, 0) for i in range(6) for j in range(5)):
            point = FreeCAD.Vector(*centers[x])
            self.assertLess(face.Surface.projectPoint(point).distanceToPoint(point), 1e-9)  # layer 0 on the face
        # the face's own normal at A, turned into the body (Part's normals point out of the solid)
        inward = -face.normalAt(*face.Surface.parameter(FreeCAD.Vector(*centers[0])))
        self.assertGreater(abs(np.dot(field.normal, tuple(inward))), 1.0 - 1e-12)
        for k in (1, 2):  # layer k: the field's map through A moved 1.5 k into the body
            a_k = np.asarray(centers[0]) + 1.5 * k * np.asarray(tuple(inward))
            layer = sl.BecotsMap.from_field(field.apex, field.axis, a_k, field.log_u, field.log_v)
            for i, j in [(0, 0), (5, 0), (2, 4), (5, 4)]:
                self.assertTrue(close(centers[lat.ball_index(i, j, k, 0)], layer.map((i / 6, j / 5))))

    def test_a_planar_face_and_faces_that_cannot_carry_it(self):
        box = self.doc.addObject("Part::Box", "Box")
        box.Length, box.Width, box.Height = 40, 30, 10
        sphere = self.doc.addObject("Part::Sphere", "Ball")
        self.doc.recompute()
        top = [n for n, f in enumerate(box.Shape.Faces) if f.CenterOfMass.z > 9.9][0]
        corners = [FreeCAD.Vector(2, 2, 13), FreeCAD.Vector(2, 28, 12), FreeCAD.Vector(38, 27, 14),
                   FreeCAD.Vector(36, 3, 11)]
        obj, lat = self.laid((box, "Face%d" % (top + 1)), corners, layer_offset=2.0)
        centers, _ = lat.balls()
        on_face = [FreeCAD.Vector(p.x, p.y, 10.0) for p in corners]  # the corners projected onto the top face
        field = curved_lattice.becots_map(obj, on_face)
        self.assertTrue(field.is_flat)
        z = centers[[lat.ball_index(i, j, 0, 0) for i in range(6) for j in range(5)], 2]
        self.assertLess(np.abs(z - 10.0).max(), 1e-9)  # layer 0 on the face
        self.assertTrue(close(centers[lat.ball_index(0, 0, 0, 0)], (2, 2, 10)))
        # layer k: the field's map through A moved 2 k down into the box; like every BeCOTS stack its layers
        # share the field, so away from A the offset is scaled by the field's dilation (the raised maps are cones)
        for k in (1, 2):
            layer = sl.BecotsMap.from_field(field.apex, field.axis, (2, 2, 10 - 2.0 * k), field.log_u, field.log_v)
            for i, j in [(0, 0), (5, 0), (2, 4), (5, 4)]:
                self.assertTrue(close(centers[lat.ball_index(i, j, k, 0)], layer.map((i / 6, j / 5))), (i, j, k))
            self.assertLess(centers[lat.ball_index(3, 2, k, 0)][2], 10.0 - k)  # below the face, inside the box
        obj.FaceLink = (sphere, ["Face1"])
        self.doc.recompute()
        self.assertFalse(obj.isValid())
        self.assertIn("FaceLink", obj.getStatusString())
        obj.FaceLink = (box, ["Edge1"])
        self.doc.recompute()
        self.assertFalse(obj.isValid())
        self.assertIn("FaceLink: link one face", obj.getStatusString())
        obj.FaceLink = None
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())


def corner_points_of(obj):
    return [tuple(p) for p in curved_lattice.corner_points(obj)]
