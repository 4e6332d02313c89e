"""Runs the GUI tests in a real FreeCAD window (under Xvfb):

    xvfb-run -a freecad -M Mod/LatticeWorkbench tests/gui/run_gui_tests.py

Environment as for tests/freecad/run_tests.py (STEADY_BUILD_PYTHON, STEADY_MOD_DIR); STEADY_SCREENSHOT_DIR
is where screenshots go (default: a temporary folder). Exits FreeCAD with the unittest result.
"""
import os
import sys
import traceback
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
for variable in ("STEADY_MOD_DIR", "STEADY_BUILD_PYTHON"):
    if os.environ.get(variable):
        sys.path.insert(0, os.environ[variable])
sys.path.insert(0, HERE)

status = 1
try:
    suite = unittest.defaultTestLoader.discover(HERE, pattern=os.environ.get("STEADY_TEST_PATTERN", "test_*.py"))
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    print("FreeCAD GUI tests: %d run, %d failures, %d errors"
          % (result.testsRun, len(result.failures), len(result.errors)))
    status = 0 if result.wasSuccessful() and result.testsRun > 0 else 1
except BaseException:
    traceback.print_exc()
sys.stdout.flush()
os._exit(status)
