"""Runs the GUI tests in a real FreeCAD window (started by tests/gui/run_gui.sh under Xvfb); see
tests/freecad/unittest_runner.py. STEADY_SCREENSHOT_DIR is where screenshots go."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, os.pardir, "freecad"))
import unittest_runner  # noqa: E402

unittest_runner.run(HERE, "FreeCAD GUI tests")
