"""Mass properties and density targets in FreeCAD: the closed form against OpenCASCADE on the exact B-rep, parts
by B-rep integration, compounds against hand values, density and mass targets, non-clean lattices refused."""
import unittest

import numpy as np

import FreeCAD
import Part

from latticewb import api
from latticewb.kernel import mass as mass_properties


class MassPropertiesTest(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("MassTest")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_closed_form_matches_opencascade_on_the_exact_brep(self):
        lat = api.make_lattice(self.doc, preset="BCC", cells=(3, 2, 2), cell_size=8.0, node_radius=1.6,
                               beam_radius=0.6, taper_u=-3.0, twist_w=4.0)
        lat.Density = 4.43
        self.doc.recompute()
        p = api.properties(lat)
        shape = Part.Shape()
        shape.importBrepFromString(api.lattice(lat).brep())
        self.assertTrue(shape.isValid())
        self.assertEqual(len(shape.Solids), 1)
        solid = shape.Solids[0]
        self.assertAlmostEqual(p["volume"], solid.Volume, delta=1e-6 * solid.Volume)
        self.assertAlmostEqual(p["area"], solid.Area, delta=1e-6 * solid.Area)
        self.assertLess(np.linalg.norm(np.array(p["centroid"]) - np.array(solid.CenterOfMass)), 1e-6)
        occ = np.array([[solid.MatrixOfInertia.A[4 * r + c] for c in range(3)] for r in range(3)])
        self.assertLess(np.abs(np.array(p["inertia"]) / (4.43e-6) - occ).max(), 1e-5 * np.abs(occ).max())
        self.assertAlmostEqual(p["mass"], 4.43e-6 * p["volume"], places=15)

    def test_part_properties_by_brep_integration(self):
        lat = api.make_lattice(self.doc, preset="cubic", cells=(3, 3, 2), cell_size=10.0, node_radius=2.0,
                               beam_radius=1.0)
        body = self.doc.addObject("Part::Box", "Box")
        body.Length, body.Width, body.Height = 25, 25, 15
        part = api.make_part(self.doc, lat, body)
        self.doc.recompute()
        p = api.properties(part)
        self.assertAlmostEqual(p["volume"], part.Shape.Volume, places=6)
        self.assertTrue(body.Shape.BoundBox.isInside(FreeCAD.Vector(*p["centroid"])))

    def test_compound_inertia_about_the_common_centroid(self):
        a = Part.makeBox(2, 1, 1)
        b = Part.makeBox(2, 1, 1, FreeCAD.Vector(0, 3, 0))
        compound = Part.Compound([a, b])
        centroid = mass_properties._compound_centroid(compound)
        self.assertAlmostEqual(centroid[1], 2.0)
        m = mass_properties._compound_inertia(compound, centroid)
        # by hand: each box 2 x 1 x 1 (volume 2) about its own centre, plus 2 * 1.5^2 for the offset along y
        ixx = 2 * (2 * (1 + 1) / 12 + 2 * 1.5 ** 2)
        izz = 2 * (2 * (4 + 1) / 12 + 2 * 1.5 ** 2)
        self.assertAlmostEqual(m.A[0], ixx, places=9)
        self.assertAlmostEqual(m.A[10], izz, places=9)

    def test_density_and_mass_targets(self):
        lat = api.make_lattice(self.doc, preset="octet", cells=(4, 4, 4), cell_size=10.0, node_radius=1.2,
                               beam_radius=0.5, taper_w=-2.0)
        lat.Density = 4.43
        self.doc.recompute()
        envelope = mass_properties.cells_envelope_volume(lat)
        # the envelope of a tapered lattice: layer k of cells is 0.98^k the size of the first
        self.assertAlmostEqual(envelope, 1000.0 * 16 * sum(0.98 ** (3 * k) for k in range(4)), places=6)
        scale = api.target_density(lat, relative_density=0.08)
        self.doc.recompute()
        self.assertAlmostEqual(api.properties(lat)["volume"] / envelope, 0.08, delta=1e-8)
        self.assertAlmostEqual(lat.NodeRadius.Value, 1.2 * scale, places=9)
        api.target_density(lat, mass=0.010)  # 10 g of Ti-6Al-4V
        self.doc.recompute()
        self.assertAlmostEqual(api.properties(lat)["mass"], 0.010, delta=1e-9)
        with self.assertRaises(ValueError):
            api.target_density(lat, relative_density=1.5)
        with self.assertRaises(ValueError):
            api.target_density(lat)

    def test_overlapping_hubs_are_reported_and_united(self):
        # face diagonals 0.5 thick, 1.41 apart at the corners: stumps of neighbouring hubs overlap
        lat = api.make_lattice(self.doc, preset="FCC", cells=(1, 1, 1), cell_size=2.0, node_radius=0.6,
                               beam_radius=0.5)
        self.doc.recompute()
        p = api.properties(lat)
        self.assertGreater(p["overlaps"], 0)
        # the crowded hubs' stumps meet past the mid-planes: cuts moved, no Boolean (else the union of the clusters)
        self.assertIn("beam cuts moved past crowded hubs", p["method"])
        # Independent answer: OpenCASCADE's fuse of every ball and beam of the lattice.
        k = api.lattice(lat)
        centers, radii = k.balls()
        starts, ends, ra, rb = k.beams()
        solids = [Part.makeSphere(float(r), FreeCAD.Vector(*map(float, c))) for c, r in zip(centers, radii)]
        for a, b, r0, r1 in zip(starts, ends, ra, rb):
            pa, pb = FreeCAD.Vector(*map(float, centers[a])), FreeCAD.Vector(*map(float, centers[b]))
            axis = pb - pa
            length = axis.Length
            axis.normalize()
            solids.append(Part.makeCylinder(float(r0), length, pa, axis) if abs(r0 - r1) < 1e-12 else
                          Part.makeCone(float(r0), float(r1), length, pa, axis))
        fused = solids[0].fuse(solids[1:])
        self.assertTrue(fused.isValid())
        self.assertAlmostEqual(p["volume"], fused.Volume, delta=1e-6 * fused.Volume)
        self.assertAlmostEqual(p["area"], fused.Area, delta=1e-6 * fused.Area)


if __name__ == "__main__":
    unittest.main()
