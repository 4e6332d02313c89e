"""Every macro in examples/ runs and writes what it says (each example's main() returns its main output)."""
import glob
import os
import runpy
import tempfile
import unittest

import FreeCAD

EXAMPLES = os.path.join(os.environ.get("STEADY_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")),
                        "examples")


class ExamplesTest(unittest.TestCase):
    def test_every_example_runs(self):
        paths = sorted(glob.glob(os.path.join(EXAMPLES, "*.py")))
        self.assertTrue(paths, "no examples found in %s" % EXAMPLES)
        for path in paths:
            with self.subTest(example=os.path.basename(path)):
                out = tempfile.mkdtemp()
                os.environ["LATTICE_OUT"] = out
                before = set(FreeCAD.listDocuments())
                try:
                    module = runpy.run_path(path, run_name="example_under_test")
                    result = module["main"]()
                finally:
                    del os.environ["LATTICE_OUT"]
                    for name in set(FreeCAD.listDocuments()) - before:
                        FreeCAD.closeDocument(name)
                self.assertTrue(os.path.isfile(result), result)
                self.assertGreater(os.path.getsize(result), 200)  # more than a header: real content
                self.assertTrue(result.startswith(out))
