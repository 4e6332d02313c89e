"""The workbench finds its icons wherever the package sits (a checkout, the installed Mod folder, a symlink)."""
import os
import unittest

from latticewb.utils import resources


class ResourcesTest(unittest.TestCase):
    def test_every_icon_the_workbench_names_exists(self):
        names = ["LatticeWorkbench", "SteadyLattice", "LatticeFilter", "LatticePart", "Properties", "DensityTarget",
                 "Export"]
        for name in names:
            self.assertTrue(os.path.isfile(resources.icon(name)), resources.icon(name))
