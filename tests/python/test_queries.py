"""Queries from Python against numpy brute force over balls() and beams(): ball interference (every
method), point membership, distance, rays, voxels; filters and filtered lattices; bad input."""
import math
import os

import numpy as np
import pytest

import steadylattice as sl
from brute_force import Elements as Brute
from conftest import cubic_lattice, random_similarity

METHODS = ["naive", "rows", "rows-paper", "blocks", "auto"]


def random_lattice(rng, kind):
    nodes = [(tuple(rng.uniform(-0.3, 0.3, 3)), rng.uniform(0.05, 0.2)) for _ in range(rng.integers(1, 3))]
    beams = [(0, 1, 0, 0, 0), (0, 0, 1, 0, 0), (0, 0, 0, 1, len(nodes) - 1)]
    if len(nodes) > 1:
        beams.append((0, 0, 0, 0, 1, nodes[0][1] * 0.5, nodes[1][1] * 0.5))
    steps = []
    for axis in range(3):
        move = np.zeros(3)
        move[axis] = 1.3
        s = random_similarity(rng, kind + axis)
        # A small version of the random step (its 0.15 power), moved along its own axis.
        steps.append(sl.Similarity.translation(move) * s.power(0.15))
    counts = tuple(int(x) for x in rng.integers(1, 5, 3))
    omitted = [(0, 0, 0, 0)] if rng.uniform() < 0.3 and counts != (1, 1, 1) else None
    return sl.Lattice(nodes, beams, counts, *steps, G=random_similarity(rng, kind), omitted=omitted)


def near_queries(rng, lat, n):
    c, r = lat.balls()
    for q in range(n):
        e = rng.integers(len(c))
        yield c[e] + rng.uniform(-3, 3, 3) * r[e], (0.0 if q % 7 == 0 else rng.uniform(0, 2) * r[e])


def check_query(lat, brute, center, radius, method):
    balls, beams = lat.query_ball(center, radius, method=method)
    assert balls.dtype == np.int64 and beams.dtype == np.int64
    assert np.all(np.diff(balls) > 0) and np.all(np.diff(beams) > 0)
    sure_b, edge_b, sure_e, edge_e = brute.query(center, radius)
    assert set(sure_b) <= set(balls) <= set(sure_b) | set(edge_b)
    assert set(sure_e) <= set(beams) <= set(sure_e) | set(edge_e)


def test_query_ball_matches_brute_force_on_random_lattices(rng):
    queries = 0
    for kind in range(36):
        lat = random_lattice(rng, kind)
        brute = Brute(lat)
        plan = lat.query_plan()
        methods = METHODS + (["slabs", "slabs-paper"] if plan["slabs"] else []) + (["constant"] if plan["constant"] else [])
        for center, radius in near_queries(rng, lat, 40):
            for m in methods:
                check_query(lat, brute, center, radius, m)
            queries += 1
    assert queries >= 1000


def test_benchmark_classes_use_their_fast_paths(rng):
    lat = cubic_lattice((6, 5, 4), 0.15)
    assert lat.query_plan()["automatic"] == "constant"
    brute = Brute(lat)
    for center, radius in near_queries(rng, lat, 200):
        check_query(lat, brute, center, radius, "constant")
    # A twisted lattice: no invariant maps, the hierarchical blocks.
    twist = sl.Lattice([((0, 0, 0), 0.1)], [(0, 1, 0, 0, 0), (0, 0, 1, 0, 0), (0, 0, 0, 1, 0)], (5, 5, 5),
                       sl.Similarity.translation((1, 0, 0)),
                       sl.Similarity.screw(0.1, (0, 1, 0), (2, 0, 2), 1.0),
                       sl.Similarity.swirl(0.15, (0, 0, 1), (2, 2, -6), 1.05))
    plan = twist.query_plan()
    assert plan["automatic"] == "blocks" and not plan["constant"]
    assert "unchanged" in plan["constant_reason"]
    brute = Brute(twist)
    for center, radius in near_queries(rng, twist, 200):
        check_query(twist, brute, center, radius, "auto")
    with pytest.raises(ValueError, match="method"):
        twist.query_ball((0, 0, 0), 1.0, method="constant")


def test_contains_distance_rays_voxels(rng):
    lat = random_lattice(rng, 4)
    brute = Brute(lat)
    c, r = lat.balls()
    pts = np.array([c[rng.integers(len(c))] + rng.uniform(-2, 2, 3) * 0.2 for _ in range(300)])
    inside = lat.contains(pts)
    dist = lat.distance(pts)
    near = lat.distance(pts, bound=0.05)
    for p, i, d, n in zip(pts, inside, dist, near):
        expect = brute.distance(p)
        assert d == pytest.approx(expect, abs=1e-7)
        assert bool(i) == (expect == 0.0) or abs(expect) < 1e-7
        assert (n == np.inf) == (expect > 0.05) or abs(expect - 0.05) < 1e-7
    assert isinstance(lat.contains(c[0]), bool) and lat.contains(c[0])
    assert isinstance(lat.distance(c[0]), float)
    # Rays toward balls: the hit point is on the boundary and no earlier point along the ray is inside.
    origins = c[:20] + 5.0
    dirs = c[:20] - origins
    t = lat.raycast(origins, dirs)
    for o, d, tt in zip(origins, dirs, t):
        u = d / np.linalg.norm(d)
        assert np.isfinite(tt)
        assert brute.distance(o + tt * u) == pytest.approx(0.0, abs=1e-7)
        assert all(brute.distance(o + s * u) > 0 for s in np.linspace(0, tt, 30)[:-1])
    assert lat.raycast(origins[0], -dirs[0]) == np.inf
    lo, hi = c.min(axis=0) - 0.3, c.max(axis=0) + 0.3
    vox = lat.voxelize(lo, hi, (9, 7, 5))
    assert vox.shape == (9, 7, 5) and vox.dtype == bool
    cell = (hi - lo) / np.array([9, 7, 5])
    centers = np.array([lo + (np.array(ix) + 0.5) * cell for ix in np.ndindex(9, 7, 5)])
    assert np.array_equal(vox.ravel(), lat.contains(centers))


def test_filters_and_lattice_in_lattice():
    fine = cubic_lattice((9, 9, 9), 0.1)
    t = sl.Similarity.translation
    coarse = sl.Lattice([((0, 0, 0), 0.6)], [(0, 1, 0, 0, 0), (0, 0, 1, 0, 0), (0, 0, 0, 1, 0)], (3, 3, 3),
                        t((4, 0, 0)), t((0, 4, 0)), t((0, 0, 4)))
    lil = sl.FilteredLattice(fine, sl.LatticeInLattice(coarse))
    balls, beams = lil.ball_mask(), lil.beam_mask()
    cb = Brute(coarse)
    c, r = fine.balls()
    for i in range(len(c)):
        d = min(cb.ball_distances(c[i]).min(), cb.beam_distances(c[i]).min())
        assert bool(balls[i]) == (d <= r[i]) or abs(d - r[i]) < 1e-9
    a, b, _, _ = fine.beams()
    assert np.array_equal(beams, balls[a] & balls[b])
    assert 0 < balls.sum() < len(balls)
    # Filtered queries: the unfiltered answer restricted to the masks (indices stay unfiltered).
    for center in c[::37]:
        fb, fe = lil.query_ball(center, 0.3)
        ub, ue = fine.query_ball(center, 0.3)
        assert np.array_equal(fb, ub[balls[ub]]) and np.array_equal(fe, ue[beams[ue]])
    # Cascade: a finer lattice inside the LiL, materialized first.
    lil.materialize()
    assert lil.materialized
    finer = cubic_lattice((17, 17, 17), 0.05)
    cascade = finer.filtered(sl.LatticeInLattice(lil))
    assert 0 < cascade.ball_mask().sum() < finer.ball_count
    # A filtered coarse lattice is materialized when a LiL filter is made from it; same answer either way.
    fresh = sl.FilteredLattice(fine, sl.LatticeInLattice(coarse))
    assert not fresh.materialized
    again = finer.filtered(sl.LatticeInLattice(fresh))
    assert fresh.materialized
    assert np.array_equal(again.ball_mask(), cascade.ball_mask())
    # Stencils, gyroids, Python bodies and their combinations.
    stencil = sl.IndexStencil(np.array([[[1]], [[0]]], bool))
    sb = fine.filtered(stencil).ball_mask()
    ids = np.array([fine.ball_id(i) for i in range(fine.ball_count)])
    assert np.array_equal(sb, ids[:, 0] % 2 == 0)
    half = sl.InsideBody(lambda p: p[:, 2] < 3.5)
    both = fine.filtered(stencil & half).ball_mask()
    assert np.array_equal(both, sb & (c[:, 2] < 3.5))
    either = fine.filtered(stencil | ~half).ball_mask()
    assert np.array_equal(either, sb | (c[:, 2] >= 3.5))
    g = fine.filtered(sl.Gyroid(4.0, 0.4)).ball_mask()
    x = c * 2 * math.pi / 4.0
    gy = np.sin(x[:, 0]) * np.cos(x[:, 1]) + np.sin(x[:, 1]) * np.cos(x[:, 2]) + np.sin(x[:, 2]) * np.cos(x[:, 0])
    assert np.array_equal(g, np.abs(gy) <= 0.4)
    assert "gyroid" in repr(sl.Gyroid(4.0, 0.4))


def test_bad_input():
    lat = cubic_lattice()
    with pytest.raises(ValueError, match="radius"):
        lat.query_ball((0, 0, 0), -1.0)
    with pytest.raises(ValueError, match="radius"):
        lat.query_ball((0, 0, 0), float("nan"))
    with pytest.raises(ValueError, match="center"):
        lat.query_ball((0, float("nan"), 0), 1.0)
    with pytest.raises(ValueError, match="points"):
        lat.contains([[0, 0, float("nan")]])
    with pytest.raises(ValueError, match="points"):
        lat.contains([[0, 0]])
    with pytest.raises(ValueError, match="bound"):
        lat.distance([[0, 0, 0]], bound=-1.0)
    with pytest.raises(ValueError, match="directions"):
        lat.raycast([[0, 0, 0]], [[0, 0, 0]])
    with pytest.raises(ValueError, match="shape"):
        lat.voxelize((0, 0, 0), (1, 1, 1), (2, 0, 2))
    with pytest.raises(ValueError, match="hi"):
        lat.voxelize((0, 0, 0), (-1, 1, 1), (2, 2, 2))
    with pytest.raises(ValueError, match="method"):
        lat.query_ball((0, 0, 0), 1.0, method="fastest")
    # An empty lattice: every node omitted.
    t = sl.Similarity.translation
    empty = sl.Lattice([((0, 0, 0), 0.1)], [], (1, 1, 2), t((1, 0, 0)), t((0, 1, 0)), t((0, 0, 1)),
                       omitted=[(0, 0, 0, 0), (0, 0, 1, 0)])
    with pytest.raises(ValueError, match="lattice"):
        empty.query_ball((0, 0, 0), 1.0)
    with pytest.raises(ValueError, match="lattice"):
        empty.contains([[0, 0, 0]])
    # Degenerate similarities are refused when they are made.
    with pytest.raises(ValueError, match="scale"):
        sl.Similarity.dilation(0.0, (0, 0, 0))
    with pytest.raises(ValueError, match="body"):
        sl.InsideBody("this is not B-rep text")
    with pytest.raises(ValueError, match="body"):
        sl.InsideBody(42)
    with pytest.raises(ValueError, match="mask"):
        sl.IndexStencil(np.ones((2, 2), bool))
    with pytest.raises(ValueError, match="body"):
        lat.filtered(sl.InsideBody(lambda p: np.ones(len(p) + 1, bool))).ball_mask()


def test_a_steep_dilation_that_loads_can_be_queried():
    """Found by the lattice-file fuzzer (tests/fuzz/findings/json_query_power_out_of_range.json): a lattice whose U
    step scales by e^6.01 loads, but its queries tabulated step powers past its groups (the neighbour margin), where
    a translation leaves the supported range, and refused ("similarity: its translation: is 1.8e+12 ..."). The
    tables now stop short of such powers; every element is still found, on every query path."""
    path = os.path.join(os.path.dirname(__file__), "..", "fuzz", "findings", "json_query_power_out_of_range.json")
    with open(path) as f:
        lat = sl.Lattice.from_json(f.read())
    brute = Brute(lat)
    plan = lat.query_plan()
    methods = METHODS + (["slabs", "slabs-paper"] if plan["slabs"] else []) + (["constant"] if plan["constant"] else [])
    centers, radii = lat.balls()
    for center, radius in [(c, 2.0 * r) for c, r in zip(centers[::5], radii[::5])] + [((0, 0, 0), 1.0)]:
        for m in methods:
            check_query(lat, brute, center, radius, m)
    assert np.all(lat.contains(centers))
