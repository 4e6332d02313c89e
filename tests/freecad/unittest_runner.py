"""The test runner shared by the App tests (freecad -c) and the GUI tests (a real window).

FreeCAD ignores PYTHONPATH and exits 0 when a script raises, so the runner puts the checkout's workbench and the
build's module first on sys.path itself (STEADY_MOD_DIR, STEADY_BUILD_PYTHON) and ends FreeCAD with the unittest
result. STEADY_TEST_PATTERN selects test files (default test_*.py)."""
import os
import sys
import traceback
import unittest


def run(folder, label):
    for variable in ("STEADY_MOD_DIR", "STEADY_BUILD_PYTHON"):
        if os.environ.get(variable):
            sys.path.insert(0, os.environ[variable])
    sys.path.insert(0, folder)
    # tests/common: the brute-force twins shared with the module's tests
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
    status = 1
    try:
        pattern = os.environ.get("STEADY_TEST_PATTERN", "test_*.py")
        suite = unittest.defaultTestLoader.discover(folder, pattern=pattern)
        result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
        print("%s: %d run, %d failures, %d errors, %d skipped"
              % (label, result.testsRun, len(result.failures), len(result.errors), len(result.skipped)))
        status = 0 if result.wasSuccessful() and result.testsRun > 0 else 1
    except BaseException:
        traceback.print_exc()
    sys.stdout.flush()
    os._exit(status)
