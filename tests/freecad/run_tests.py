"""Runs the workbench's App tests inside FreeCAD: freecad -c tests/freecad/run_tests.py

Environment: STEADY_BUILD_PYTHON (folder of the built steadylattice module) and STEADY_MOD_DIR (the checkout's
Mod/LatticeWorkbench) are put first on sys.path, so the tests use this checkout, not an installed copy.
STEADY_TEST_PATTERN selects test files (default test_*.py). freecad -c exits 0 when a script raises, so this
runner exits explicitly with the unittest result.
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
    print("FreeCAD tests: %d run, %d failures, %d errors, %d skipped"
          % (result.testsRun, len(result.failures), len(result.errors), len(result.skipped)))
    status = 0 if result.wasSuccessful() and result.testsRun > 0 else 1
except BaseException:
    traceback.print_exc()
sys.stdout.flush()
os._exit(status)
