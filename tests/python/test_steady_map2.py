"""Steady 2-maps and rectified steady slabs through the module: the five points interpolated, the slab an ordinary
Lattice (queries, properties and B-rep agree), ValueError naming the points."""
import numpy as np
import pytest

import steadylattice as sl

# A warped square: M(0,0), M(1,0), M(0,1), M(1,1) and M(1/2, 0) off the segment ab.
POINTS = ((0.0, 0.0), (10.0, 1.0), (-1.0, 9.0), (8.0, 11.0), (5.2, 1.4))


def test_five_points_are_interpolated():
    m = sl.SteadyMap2.from_points(*POINTS)
    uv = np.array([[0, 0], [1, 0], [0, 1], [1, 1], [0.5, 0]], dtype=float)
    images = m.map(uv)
    assert images.shape == (5, 3)
    expected = np.array([[x, y, 0.0] for x, y in POINTS[:4] + (POINTS[4],)])
    assert np.abs(images - expected).max() < 1e-12
    # U applied first: M(u, v) = V^v(U^u(O))
    u, v = 0.3, 0.7
    direct = m.v_similarity.power(v).apply(m.u_similarity.power(u).apply(m.origin))
    assert np.abs(m.map((u, v)) - direct).max() < 1e-12
    assert m.unit == pytest.approx(np.hypot(10.0, 1.0), rel=1e-12)


def test_rectified_slab_is_an_ordinary_lattice(rng):
    m = sl.SteadyMap2.from_points(*POINTS)
    lat = m.slab([((0.5, 0.5, 0.0), 0.03)], [(0, 1, 0, 0, 0), (0, 0, 1, 0, 0)], (7, 6, 1), beam_ratio=0.5)
    centers, radii = lat.balls()
    assert len(radii) == 42
    template = m.rectify((0.5 / 7, 0.5 / 6, 0.0), 0.03)
    assert np.abs(centers[lat.ball_index(0, 0, 0, 0)] - template[0]).max() < 1e-12
    placed = m.field(3 / 7, 2 / 6).apply(template[0])
    assert np.abs(centers[lat.ball_index(3, 2, 0, 0)] - placed).max() < 1e-12
    for _ in range(30):
        c = centers[rng.integers(len(radii))] + rng.uniform(-0.5, 0.5, 3)
        r = rng.uniform(0, 0.6)
        auto, naive = lat.query_ball(c, r), lat.query_ball(c, r, method="naive")
        assert np.array_equal(auto[0], naive[0]) and np.array_equal(auto[1], naive[1])
    exact = lat.properties()["volume"]
    assert exact == pytest.approx(lat.properties_brute_force()["volume"], rel=1e-10)
    props = sl.brep_properties(lat.brep())
    assert props["valid"] and props["solids"] == 1
    assert props["volume"] == pytest.approx(exact, rel=1e-7)


def test_three_frames():
    a = ((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1))
    b = ((2, 0, 0.5), (0.88, 0.66, 0), (-0.66, 0.88, 0), (0, 0, 1.1))
    c = ((0, 1.5, 0.3), (1, 0, 0), (0, 0.8, 0.6), (0, -0.6, 0.8))
    m = sl.SteadyMap2.from_frames(a, b, c)
    assert np.abs(m.map((1, 0)) - (2, 0, 0.5)).max() < 1e-12
    assert np.abs(m.map((0, 1)) - (0, 1.5, 0.3)).max() < 1e-12


def test_bad_input_names_the_points():
    a, b, c, d, e = POINTS
    with pytest.raises(ValueError, match="a, e"):
        sl.SteadyMap2.from_points(a, b, c, d, a)
    with pytest.raises(ValueError, match="c, d"):
        sl.SteadyMap2.from_points(a, b, c, c, e)
    with pytest.raises(ValueError, match="e"):
        sl.SteadyMap2.from_points(a, b, c, d, (float("nan"), 0.0))
    m = sl.SteadyMap2.from_points(*POINTS)
    with pytest.raises(ValueError, match="counts.w"):
        m.slab([((0.5, 0.5, 0.0), 0.03)], [], (2, 2, 2))
    with pytest.raises(ValueError, match=r"nodes\[0\].radius"):
        m.slab([((0.5, 0.5, 0.0), -0.03)], [], (2, 2, 1))
    with pytest.raises(ValueError, match="method"):
        m.rectify((0.5, 0.5, 0.0), 0.03, method="three points")


def test_least_squares_rectification_is_centred_where_the_map_is_nearly_linear():
    m = sl.SteadyMap2.from_points(*POINTS)
    c = (0.4, 0.6, 0.1)
    four = m.rectify(c, 1e-4)
    fit = m.rectify(c, 1e-4, method="least squares")
    warped = m.warp(c)
    assert np.linalg.norm(fit[0] - warped) < 1e-2 * fit[1] < np.linalg.norm(four[0] - warped)
    lat = m.slab([((0.5, 0.5, 0.0), 0.03)], [(0, 1, 0, 0, 0)], (3, 2, 1), beam_ratio=0.5, method="least squares")
    assert lat.ball_count == 6
