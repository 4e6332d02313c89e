"""Connectors of a constant-radius BeCOTS lattice read by FreeCAD: the STEP assembly (a part per family placed at
each member, and the rods) and one family's file come back through FreeCAD's own reader (Part.read) with every
solid valid and the volumes written."""
import os
import tempfile
import unittest

import numpy as np

import Part

import steadylattice as sl


class ConnectorStepTest(unittest.TestCase):
    def test_connector_step_files_read_back_in_freecad(self):
        m = sl.BecotsMap((0, 0, 0), (0.1, 1, 0.2), (1.3, 1.2, -0.3), (1, 0, 0.1))
        lat = sl.becots_lattice(m, sl.becots_connectivity("kagome"), (3, 2, 1), 0.01)
        centers, _ = lat.balls()
        a, b, _, _ = lat.beams()
        rho = float(np.min(np.linalg.norm(centers[b] - centers[a], axis=1))) / 10
        low, high = lat.connector_reach_range(rho)
        c = lat.connectors(rho, reach=0.5 * (low + high))
        families = c.families
        folder = tempfile.mkdtemp()
        path = os.path.join(folder, "connectors.step")
        c.write_step(path)
        back = Part.read(path)
        self.assertEqual(len(back.Solids), lat.ball_count + lat.beam_count)
        for solid in back.Solids:
            self.assertTrue(solid.isValid())
        # Volumes by adaptive integration (FreeCAD's Shape.Volume uses a coarser rule, brep_io.hpp).
        total = sum(sl.brep_properties(s.exportBrepToString())["volume"] for s in back.Solids)
        written = sum(f["volume"] * f["count"] for f in families) + sum(
            np.pi * rho * rho * e["length"] * e["count"] for e in c.cut_list)
        self.assertAlmostEqual(total, written, delta=1e-6 * written)
        one = os.path.join(folder, "family.step")
        c.write_family_step(0, one)
        solid = Part.read(one)
        self.assertEqual(len(solid.Solids), 1)
        self.assertTrue(solid.Solids[0].isValid())
        volume = sl.brep_properties(solid.Solids[0].exportBrepToString())["volume"]
        self.assertAlmostEqual(volume, families[0]["volume"], delta=1e-6 * volume)


if __name__ == "__main__":
    unittest.main()
