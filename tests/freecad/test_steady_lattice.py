"""SteadyLattice inside FreeCAD: create, edit, recompute, bad input, save and reload, export."""
import math
import os
import tempfile
import unittest

import FreeCAD
import Part

import steadylattice as sl
from latticewb import api
from latticewb.kernel import presets


def lattice_points(preset, cells):
    """Brute force: every basis point of every cell corner group that lies inside the box of cells, as
    (position in cell fractions, basis index)."""
    basis = presets.PRESETS[preset][0]
    points = []
    for i in range(cells[0] + 1):
        for j in range(cells[1] + 1):
            for k in range(cells[2] + 1):
                for n, b in enumerate(basis):
                    p = (i + b[0], j + b[1], k + b[2])
                    if all(x <= c + 1e-12 for x, c in zip(p, cells)):
                        points.append((p, n))
    return points


def expected_ball_count(preset, cells):
    return len(lattice_points(preset, cells))


def expected_beam_count(preset, cells):
    """Brute force over all pairs of points: those at the preset's neighbour distance (for FCC only pairs with a
    cell corner at one end). Independent of the beam patterns the preset generates."""
    _, aspect, distance, which = presets.PRESETS[preset]
    points = lattice_points(preset, cells)
    count = 0
    for q, (p1, n1) in enumerate(points):
        for p2, n2 in points[q + 1:]:
            d = math.sqrt(sum(((x - y) * a) ** 2 for x, y, a in zip(p1, p2, aspect)))
            if abs(d - distance) < 1e-9 and (which == "all" or 0 in (n1, n2)):
                count += 1
    return count


class SteadyLatticeTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("SteadyLatticeTest")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_presets_build_the_expected_elements(self):
        for preset in presets.PRESET_NAMES:
            cells = (3, 2, 2)
            obj = api.make_lattice(self.doc, preset=preset, cells=cells, cell_size=5.0, node_radius=0.8,
                                   beam_radius=0.5)
            self.doc.recompute()
            self.assertTrue(obj.isValid(), preset)
            self.assertEqual(obj.BallCount, expected_ball_count(preset, cells), preset)
            self.assertEqual(obj.BeamCount, expected_beam_count(preset, cells), preset)
            self.assertEqual(len(obj.Shape.Solids), obj.BallCount + obj.BeamCount, preset)
            # the lattice spans the box of cells
            box = obj.Shape.BoundBox
            self.assertAlmostEqual(box.XMin, -0.8, places=6)
            aspect = presets.PRESETS[preset][1]
            self.assertAlmostEqual(box.XMax, 15.0 * aspect[0] + 0.8, places=6)

    def test_editing_recomputes(self):
        obj = api.make_lattice(self.doc, preset="cubic", cells=(2, 2, 2), cell_size=10.0, node_radius=1.0,
                               beam_radius=0.5, layout="steps")
        self.doc.recompute()
        self.assertEqual(obj.BallCount, 27)
        obj.CellsU = 4
        self.doc.recompute()
        self.assertEqual(obj.BallCount, 45)
        self.assertEqual(obj.BeamCount, expected_beam_count("cubic", (4, 2, 2)))
        # a taper of 10 % per cell along U shrinks the last balls to 0.9^4 of the first
        obj.ScaleU = 0.9
        self.doc.recompute()
        lattice = api.lattice(obj)
        _, radii = lattice.balls()
        self.assertAlmostEqual(radii.min(), 0.9 ** 4, places=12)
        # a twist of 10 degrees per cell along W turns the top layer by 20 degrees
        obj.StepW = FreeCAD.Placement(FreeCAD.Vector(0, 0, 1), FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), 10))
        obj.ScaleU = 1.0
        self.doc.recompute()
        centers, _ = api.lattice(obj).balls()
        top_corner = centers[api.lattice(obj).ball_index(4, 0, 2, 0)]
        self.assertAlmostEqual(math.degrees(math.atan2(top_corner[1], top_corner[0])), 20.0, places=9)
        # cumulative steps: the last cell lands where the step says, whatever the count
        obj.StepMode = "cumulative"
        obj.StepU = FreeCAD.Placement(FreeCAD.Vector(8, 0, 0), FreeCAD.Rotation())
        self.doc.recompute()
        lat = api.lattice(obj)
        self.assertAlmostEqual(lat.ball(4, 0, 0, 0)[0][0], 80.0, places=9)
        obj.CellsU = 8
        self.doc.recompute()
        self.assertAlmostEqual(api.lattice(obj).ball(8, 0, 0, 0)[0][0], 80.0, places=9)

    def test_custom_template(self):
        obj = api.make_lattice(self.doc, preset="custom", cells=(3, 1, 1), cell_size=10.0,
                               nodes=[FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(0.5, 0.5, 0)],
                               node_radii=[1.0, 0.7], beams=["0 1 0 0 0", "0 0 0 0 1 0.4 0.3"])
        self.doc.recompute()
        self.assertTrue(obj.isValid())
        self.assertEqual(obj.BallCount, 6)
        self.assertEqual(obj.BeamCount, 2 + 3)
        _, _, ra, rb = api.lattice(obj).beams()
        self.assertEqual(sorted(set(ra.tolist())), [0.4, 1.0])

    def test_nonsense_is_refused_or_clamped_with_a_message(self):
        obj = api.make_lattice(self.doc, preset="cubic", cells=(2, 2, 2), node_radius=1.0, beam_radius=0.5)
        self.doc.recompute()
        obj.BeamRadius = 5.0  # wider than the nodes: clamped
        self.assertAlmostEqual(obj.BeamRadius.Value, 1.0)
        obj.TaperU = -150.0  # would shrink cells to nothing: clamped
        self.assertAlmostEqual(obj.TaperU, -99.0)
        obj.TaperU = 0.0
        obj.CellSize = 0.0  # refused: the previous value comes back
        self.assertAlmostEqual(obj.CellSize.Value, 10.0)
        obj.Preset = "custom"
        before = list(obj.Beams)
        obj.Beams = ["0 1 0 0 7"]  # node 7 does not exist: refused
        self.assertEqual(list(obj.Beams), before)
        obj.Beams = ["0 1 0 0"]  # malformed: refused
        self.assertEqual(list(obj.Beams), before)
        obj.NodeRadii = [-1.0] * len(obj.Nodes)
        self.assertTrue(all(r > 0 for r in obj.NodeRadii))
        self.doc.recompute()
        self.assertTrue(obj.isValid())

    def test_kernel_errors_leave_the_document_intact(self):
        good = api.make_lattice(self.doc, preset="cubic", cells=(2, 2, 2))
        bad = api.make_lattice(self.doc, preset="custom", cells=(3, 1, 1), nodes=[FreeCAD.Vector(0, 0, 0)],
                               node_radii=[1.0], beams=["0 1 0 0 0"])
        self.doc.recompute()
        volume = good.Shape.Volume
        bad.Beams = ["0 1 0 0 0", "0 -1 0 0 0"]  # the same beams twice: only the kernel sees it
        self.doc.recompute()
        self.assertIn("Invalid", bad.State)
        self.assertTrue(good.isValid())
        self.assertAlmostEqual(good.Shape.Volume, volume)
        bad.Beams = ["0 1 0 0 0"]
        self.doc.recompute()
        self.assertTrue(bad.isValid())
        with self.assertRaises(ValueError):
            api.make_lattice(self.doc, preset="gyroid")
        with self.assertRaises(ValueError):
            api.make_lattice(self.doc, cell_sise=3)
        self.assertEqual(len(self.doc.Objects), 2)

    def test_save_and_reload(self):
        obj = api.make_lattice(self.doc, preset="BCC", cells=(2, 3, 2), cell_size=7.0, node_radius=1.1,
                               beam_radius=0.6, layout="steps", scale_v=1.05)
        obj.Placement = FreeCAD.Placement(FreeCAD.Vector(5, 6, 7), FreeCAD.Rotation(FreeCAD.Vector(1, 0, 0), 30))
        self.doc.recompute()
        volume, count, name = obj.Shape.Volume, obj.BallCount, obj.Name
        text = api.lattice(obj).to_json()
        path = os.path.join(tempfile.mkdtemp(), "lattice.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        again = self.doc.getObject(name)
        self.assertEqual(again.Preset, "BCC")
        self.assertAlmostEqual(again.ScaleV, 1.05)
        self.assertEqual(again.BallCount, count)
        again.touch()
        self.doc.recompute()
        self.assertTrue(again.isValid())
        self.assertAlmostEqual(again.Shape.Volume, volume, places=6)
        # the placement's rotation goes through FreeCAD's file as text: compare the balls, not the bits
        before, _ = sl.Lattice.from_json(text).balls()
        after, _ = api.lattice(again).balls()
        self.assertLess(abs(after - before).max(), 1e-9)

    def test_step_and_json_export(self):
        obj = api.make_lattice(self.doc, preset="FCC", cells=(2, 2, 1), cell_size=6.0, node_radius=1.0,
                               beam_radius=0.6)
        self.doc.recompute()
        folder = tempfile.mkdtemp()
        step = api.export([obj], os.path.join(folder, "fcc.step"))
        back = Part.read(step)
        self.assertEqual(len(back.Solids), obj.BallCount + obj.BeamCount)
        self.assertAlmostEqual(back.Volume, obj.Shape.Volume, delta=1e-6 * obj.Shape.Volume)
        path = api.export([obj], os.path.join(folder, "fcc.json"))
        with open(path) as f:
            lattice = sl.Lattice.from_json(f.read())
        self.assertEqual(lattice.ball_count, obj.BallCount)
        with self.assertRaises(ValueError):
            api.export([obj], os.path.join(folder, "fcc.xyz"))


if __name__ == "__main__":
    unittest.main()
