"""Runs the workbench's App tests inside FreeCAD: freecad -c tests/freecad/run_tests.py (see unittest_runner)."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import unittest_runner  # noqa: E402

unittest_runner.run(HERE, "FreeCAD tests")
