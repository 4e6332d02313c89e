"""Shared fixtures of the module tests: the module under test and small lattices."""
import math
import os
import sys

import numpy as np
import pytest

import steadylattice as sl

# tests/common: the brute-force twins shared with the FreeCAD tests
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))


@pytest.fixture
def rng():
    return np.random.default_rng(12345)


def random_similarity(rng, kind):
    """A random similarity of one of the six kinds (kind % 6)."""
    axis = rng.normal(size=3)
    point = rng.uniform(-5, 5, size=3)
    angle = rng.uniform(-3, 3)
    scale = math.exp(rng.uniform(-0.5, 0.5))
    k = kind % 6
    if k == 0:
        return sl.Similarity.translation(rng.uniform(-3, 3, size=3))
    if k == 1:
        return sl.Similarity.rotation(angle, axis, point)
    if k == 2:
        return sl.Similarity.screw(angle, axis, point, rng.uniform(-2, 2))
    if k == 3:
        return sl.Similarity.dilation(scale, point)
    if k == 4:
        return sl.Similarity.swirl(angle, axis, point, scale)
    return sl.Similarity.swirl(angle, axis, point, scale) * sl.Similarity.translation(rng.uniform(-2, 2, size=3))


def cubic_lattice(counts=(4, 3, 2), radius=0.2):
    t = sl.Similarity.translation
    return sl.Lattice([((0, 0, 0), radius)], [(0, 1, 0, 0, 0), (0, 0, 1, 0, 0), (0, 0, 0, 1, 0)], counts,
                      t((1, 0, 0)), t((0, 1, 0)), t((0, 0, 1)))
