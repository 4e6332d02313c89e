"""The COTS and BeCOTS maps through the module: numpy in and out, every pre-image, ValueError naming the corners."""
import cmath
import math

import numpy as np
import pytest

import steadylattice as sl

# Standard case P1 of spec/cots-maps.md: M(0,0) = a, M(0,1) = b, M(1,1) = c, M(1,0) = d.
P1 = ((0.0, 0.0), (0.1, 1.0), (1.3, 1.2), (1.0, 0.0))


def test_cots_map_corners_values_and_fixed_point():
    m = sl.CotsMap(*P1)
    corners = m.map(np.array([[0, 0], [0, 1], [1, 1], [1, 0]], dtype=float))
    assert corners.shape == (4, 2)
    assert np.abs(corners - np.array(P1)).max() < 1e-14
    assert np.abs(m.map((0.5, 0.5)) - (0.5875679672498948, 0.5364601084552767)).max() < 1e-15
    assert m.map((0.5, 0.5)).shape == (2,)
    assert np.abs(m.fixed_point - (-2.75, -2.25)).max() < 1e-14
    assert abs(cmath.exp(m.log_v) - (1.2 + 0.2j)) < 1e-15
    assert m.determinant == pytest.approx(0.06277838000663953, abs=1e-15)
    assert m.area == pytest.approx(1.2029619035875445, abs=1e-14)
    assert m.tile_area(0, 0, 4, 4) == pytest.approx(0.054842766786164246, abs=1e-15)
    assert not m.is_affine and m.orientation == 1
    assert np.abs(m.corners - np.array(P1)).max() == 0.0


def test_cots_inverse_returns_every_preimage(rng):
    m = sl.CotsMap(*P1)
    uv = rng.uniform(0, 1, size=(500, 2))
    found = m.inverse(m.map(uv))
    assert isinstance(found, list) and len(found) == 500
    worst = max(np.abs(f - p).max() for f, p in zip(found, uv))
    assert all(f.shape == (1, 2) for f in found)
    assert worst < 1e-13
    single = m.inverse(m.map((0.3, 0.7)))
    assert single.shape == (1, 2) and np.abs(single[0] - (0.3, 0.7)).max() < 1e-14
    # outside the range: nothing in [0,1]^2, but the extended map finds it
    q = m.map((1.3, -0.2))
    assert m.inverse(q).shape == (0, 2)
    assert np.abs(m.inverse(q, box=(-1, 2, -1, 2))[0] - (1.3, -0.2)).max() < 1e-14


def test_cots_self_overlap_branches_and_tiles():
    spiral = sl.CotsMap.from_spiral((1, 0), (0, 0), 0.15 + 7j, 0.5 + 1j)
    m = sl.CotsMap(*spiral.corners, branches=(1, 0))
    assert abs(m.log_u - (0.15 + 7j)) < 1e-14
    q = m.map((0.95, 0.3))
    uv, branches = m.inverse(q, with_branches=True)
    assert uv.shape == (2, 2) and list(branches) == [0, 1]
    assert np.abs(uv[0] - (0.012211148, 0.581336656)).max() < 1e-9
    assert np.abs(uv[1] - (0.95, 0.3)).max() < 1e-14
    assert np.abs(m.map(uv) - q).max() < 1e-14
    assert sorted(m.tiles(q, 4, 4)) == [(0, 2), (3, 1)]


def test_cots_tiles_are_similar_and_sum_to_the_range():
    m = sl.CotsMap(*P1)
    n = 4
    s = m.tile_similarity(2, 3, n, n)
    tile00 = m.map(np.array([[0, 0], [0, 1], [1, 1], [1, 0]]) / n)
    tile23 = m.map((np.array([[0, 0], [0, 1], [1, 1], [1, 0]]) + (2, 3)) / n)
    assert np.abs(s.apply(tile00) - tile23).max() < 2e-15
    assert sum(m.tile_area(i, j, n, n) for i in range(n) for j in range(n)) == pytest.approx(m.area, abs=1e-14)
    assert np.abs(m.u_similarity.apply(np.array([P1[0], P1[1]])) - np.array([P1[3], P1[2]])).max() < 1e-15


def test_cots_area_matches_the_boundary_integral(rng):
    """The closed-form area against the shoelace sum of many boundary samples, extrapolated (Richardson)."""
    m = sl.CotsMap((0.0, 0.0), (0.3, 1.1), (1.5, 0.7), (0.9, -0.2))

    def shoelace(n):
        t = np.linspace(0, 1, n, endpoint=False)
        edges = [np.column_stack([t, 0 * t]), np.column_stack([1 + 0 * t, t]),
                 np.column_stack([1 - t, 1 + 0 * t]), np.column_stack([0 * t, 1 - t])]
        p = m.map(np.vstack(edges))
        x, y = p[:, 0], p[:, 1]
        return 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)

    coarse, fine = shoelace(4000), shoelace(8000)
    assert (4 * fine - coarse) / 3 == pytest.approx(m.area, abs=1e-10)


def test_cots_parallelogram_is_affine():
    a, b, d = np.array([0.0, 0.0]), np.array([0.5, 1.0]), np.array([1.0, 0.25])
    m = sl.CotsMap(a, b, b + d - a, d)
    assert m.is_affine and m.fixed_point is None
    assert np.abs(m.map((0.3, 0.6)) - (a + 0.3 * (d - a) + 0.6 * (b - a))).max() < 1e-15
    assert np.abs(m.inverse(m.map((0.3, 0.6)))[0] - (0.3, 0.6)).max() < 1e-15
    with pytest.raises(ValueError, match="branch"):
        sl.CotsMap(a, b, b + d - a, d, branches=(1, 0))


@pytest.mark.parametrize("corners, words", [
    (((math.nan, 0), (0.1, 1), (1.3, 1.2), (1, 0)), "corner a"),
    (((0, 0), (0, 0), (1.3, 1.2), (1, 0)), "corners a, b"),
    (((0, 0), (1, 1), (3, 3), (2, 2)), "collapses to a curve"),
])
def test_cots_bad_input_names_the_corners(corners, words):
    with pytest.raises(ValueError, match=words):
        sl.CotsMap(*corners)


def test_cots_bad_arguments():
    m = sl.CotsMap(*P1)
    with pytest.raises(ValueError, match="uv"):
        m.map(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="points"):
        m.inverse([[math.nan, 0.0]])
    with pytest.raises(ValueError, match="nu"):
        m.tiles((0.5, 0.5), 0, 2)
    with pytest.raises(TypeError):
        sl.CotsMap((0, 0), (1, 0))
    with pytest.raises(ValueError, match="corner c"):
        sl.CotsMap((0, 0), (0.1, 1), (1.3, 1.2, 5.0), (1, 0))


def becots_corners():
    return ((0.0, 0.0, 0.0), (0.1, 1.0, 0.2), (1.3, 1.2, -0.3), (1.0, 0.0, 0.1))


def test_becots_map_corners_and_inverse(rng):
    m = sl.BecotsMap(*becots_corners())
    corners = m.map(np.array([[0, 0], [0, 1], [1, 1], [1, 0]], dtype=float))
    assert corners.shape == (4, 3)
    assert np.abs(corners - np.array(becots_corners())).max() < 1e-12
    assert not m.is_flat and m.apex is not None
    uv = rng.uniform(0, 1, size=(300, 2))
    found = m.inverse(m.map(uv))
    assert max(np.min(np.abs(f - p).max(axis=1)) for f, p in zip(found, uv)) < 1e-12
    # off the cone: nothing
    assert m.inverse(m.map((0.5, 0.5)) + 1e-3 * m.axis).shape[0] == 0
    # the range lies on the cone: every point sees the axis at the bend angle from the apex
    fp = m.map(uv) - m.apex
    angles = np.arctan2(np.linalg.norm(np.cross(fp, m.axis), axis=1), fp @ m.axis)
    assert np.abs(angles - m.bend_angle).max() < 1e-12


def test_becots_field_raise_project_bend():
    m = sl.BecotsMap(*becots_corners())
    u, v = m.u_similarity, m.v_similarity
    a, b, c, d = np.array(becots_corners())
    assert np.abs(u.apply(np.array([a, b])) - np.array([d, c])).max() < 1e-12
    assert np.abs(v.apply(np.array([a, d])) - np.array([b, c])).max() < 1e-12
    assert (u * v).approx_equal(v * u, 1e-12)
    flat = m.projected()
    assert flat.is_flat and abs(flat.height) < 1e-15
    assert np.abs(flat.raised(m.height).map((0.3, 0.4)) - m.map((0.3, 0.4))).max() < 1e-12
    sheet = m.unbent()
    assert sheet.bend_angle == pytest.approx(math.pi / 2)
    assert np.abs(sheet.bent(m.bend_angle).map((0.7, 0.2)) - m.map((0.7, 0.2))).max() < 1e-12
    assert sheet.area == pytest.approx(m.area, rel=1e-12)
    with pytest.raises(ValueError, match="beta"):
        m.bent(0.0)


def test_becots_bent_sheet_overlaps_itself():
    flat = sl.BecotsMap((0, 0, 0), (0.1, 1, 0), (1.3, 1.2, 0), (1, 0, 0))
    wound = flat.bent(0.03)
    grid = np.array([(i / 10, j / 10) for i in range(11) for j in range(11)])
    found = wound.inverse(wound.map(grid))
    assert sum(len(f) > 1 for f in found) > 5
    for f, q in zip(found, wound.map(grid)):
        assert np.abs(wound.map(f) - q).max() < 1e-12


@pytest.mark.parametrize("corners, words", [
    (((math.nan, 0, 0), (0.1, 1, 0.2), (1.3, 1.2, -0.3), (1, 0, 0.1)), "corner A"),
    (((0, 0, 0), (0, 0, 0), (1.3, 1.2, -0.3), (1, 0, 0.1)), "corners A, B"),
    (((0, 0, 0), (1, 1, 1), (3, 3, 3), (2, 2, 2)), "one line"),
    (((0, 0, 0), (0, 1, 0), (1, 1, 1e-3), (1, 0, 0)), "axis"),
])
def test_becots_bad_input_names_the_corners(corners, words):
    with pytest.raises(ValueError, match=words):
        sl.BecotsMap(*corners)


def test_becots_range_finder_holds_every_interfering_ball(rng):
    m = sl.BecotsMap((0, 0, 0), (0.1, 1, 0), (1.3, 1.2, 0), (1, 0, 0)).bent(0.7)
    n = 40
    step = 1.0 / (n - 1)
    spacing = np.linalg.norm(m.map((step, 0)) - m.map((0, 0)))
    finder = sl.BecotsRangeFinder(m, [(m.map((0.3 * step, 0.4 * step)), 0.25 * spacing)], (n, n), (step, step))
    hits = 0
    for _ in range(300):
        center = m.map(rng.uniform(0, 1, 2)) + rng.uniform(-1, 1, 3) * spacing
        radius = rng.uniform(0, 2) * spacing
        fast, naive = finder.interfering(center, radius), finder.interfering_naive(center, radius)
        assert sorted(map(tuple, fast)) == sorted(map(tuple, naive))
        hits += len(naive)
        groups = sum((i1 - i0 + 1) * (j1 - j0 + 1) for i0, i1, j0, j1 in finder.candidates(center, radius))
        assert groups < n * n / 10
    assert hits > 100
    center, radius = finder.ball(3, 5, 0)
    assert radius == pytest.approx(0.25 * spacing * abs(cmath.exp((3 * m.log_u + 5 * m.log_v) * step)), rel=1e-12)
    with pytest.raises(ValueError, match="n"):
        finder.ball(0, 0, 1)
    with pytest.raises(ValueError, match="counts"):
        sl.BecotsRangeFinder(m, [((0, 0, 0), 0.1)], (0, 3), (0.1, 0.1))


def test_becots_pattern_properties_in_closed_form():
    m = sl.BecotsMap((0, 0, 0), (0.1, 1, 0.2), (1.3, 1.2, -0.3), (1, 0, 0.1))
    balls = [(m.map((0.02, 0.03)), 0.01), (m.map((0.05, 0.01)) + (0, 0, 0.01), 0.005)]
    nu, nv, du, dv = 30, 20, 1 / 29, 1 / 20
    p = sl.becots_pattern_properties(m, balls, (nu, nv), (du, dv))
    volume, moment = 0.0, np.zeros(3)
    for i in range(nu):
        for j in range(nv):
            s = m.field(i * du, j * dv)
            for c, r in balls:
                v = 4 / 3 * math.pi * (r * s.scale) ** 3
                volume += v
                moment += v * s.apply(c)
    assert p["volume"] == pytest.approx(volume, rel=1e-12)
    assert np.abs(p["centroid"] - moment / volume).max() < 1e-12
    with pytest.raises(ValueError, match="counts"):
        sl.becots_pattern_properties(m, balls, (0, 2), (0.1, 0.1))


@pytest.mark.parametrize("connectivity, hub_degree", [("triangle", 6), ("kagome", 4), ("honeycomb", 3)])
def test_becots_lattice_is_an_ordinary_lattice(connectivity, hub_degree, rng):
    m = sl.BecotsMap(*becots_corners()).unbent().bent(0.8)
    lat = sl.becots_lattice(m, connectivity, (9, 8, 2), 0.012, layer_raise=0.05, beam_ratio=0.6)
    assert lat.layout == "any-order-brick" and lat.order == "WUV"
    centers, radii = lat.balls()
    nodes, _ = sl.becots_connectivity(connectivity)
    # layer 0: every node on the map, at its tile's parameters
    s, t = nodes[0]
    assert np.abs(centers[lat.ball_index(4, 3, 0, 0)] - m.map(((4 + s) / 9, (3 + t) / 8))).max() < 1e-12
    start, end = lat.beams()[:2]
    hub = lat.ball_index(4, 4, 0, 0)
    assert np.count_nonzero(start == hub) + np.count_nonzero(end == hub) == hub_degree
    for _ in range(40):
        c = centers[rng.integers(len(centers))] + rng.uniform(-0.03, 0.03, 3)
        r = rng.uniform(0, 0.03)
        auto, naive = lat.query_ball(c, r), lat.query_ball(c, r, method="naive")
        assert np.array_equal(auto[0], naive[0]) and np.array_equal(auto[1], naive[1])


def test_becots_stack_properties_use_the_closed_form_sums():
    m = sl.BecotsMap(*becots_corners()).unbent().bent(0.8)
    nodes, beams = sl.becots_connectivity("kagome")
    beams = beams + [(n, 0, 0, 1, n) for n in range(len(nodes))]
    lat = sl.becots_lattice(m, (nodes, beams), (8, 6, 2), 0.01, layer_raise=0.08, beam_ratio=0.6)
    fast, brute = lat.properties(), lat.properties_brute_force()
    assert fast["clean_verified"]
    assert fast["volume"] == pytest.approx(brute["volume"], rel=1e-10)
    assert fast["area"] == pytest.approx(brute["area"], rel=1e-10)
    assert np.abs(np.asarray(fast["centroid"]) - np.asarray(brute["centroid"])).max() < 1e-10


def test_becots_lattice_query_equals_the_lattice_query(rng):
    m = sl.BecotsMap(*becots_corners()).unbent().bent(0.5)
    lat = sl.becots_lattice(m, "triangle", (30, 20, 1), 0.004, beam_ratio=0.6)
    q = sl.BecotsLatticeQuery(lat, m)
    centers, radii = lat.balls()
    for _ in range(60):
        c = centers[rng.integers(len(radii))] + rng.uniform(-0.05, 0.05, 3)
        r = rng.uniform(0, 0.04)
        fast, naive = q.query_ball(c, r), lat.query_ball(c, r, method="naive")
        assert np.array_equal(fast[0], naive[0]) and np.array_equal(fast[1], naive[1])
        assert q.candidate_groups(c, r) < 600
    with pytest.raises(ValueError, match="lattice"):
        sl.BecotsLatticeQuery(lat, sl.BecotsMap(*becots_corners()))


def test_becots_stack_by_normal_offset_takes_the_becots_path(rng):
    m = sl.BecotsMap(*becots_corners()).unbent().bent(0.8)
    nodes, beams = sl.becots_connectivity("kagome")
    beams = beams + [(n, 0, 0, 1, n) for n in range(len(nodes))]
    lat = sl.becots_lattice(m, (nodes, beams), (9, 8, 12), 0.01, layer_offset=0.04, beam_ratio=0.6)
    plan = lat.query_plan()
    assert plan["becots"] and plan["automatic"] == "becots", plan["becots_reason"]
    centers, _ = lat.balls()
    # layer k's corner ball: A moved k times along the range's normal at A
    assert np.abs(centers[lat.ball_index(0, 0, 5, 0)] - (m.map(((0.5 / 9), 0.0)) + 5 * 0.04 * m.normal)).max() < 1e-12
    q = sl.BecotsLatticeQuery(lat, m)
    assert q.layer_count == 12
    points = centers[rng.integers(len(centers), size=300)] + rng.uniform(-0.02, 0.02, (300, 3))
    assert np.array_equal(lat.contains(points), lat.contains(points, method="naive"))
    for p in points[:60]:
        assert len(q.candidate_layers(p, 0.0)) <= 6
        got, naive = lat.query_ball(p, 0.015), lat.query_ball(p, 0.015, method="naive")
        assert np.array_equal(got[0], naive[0]) and np.array_equal(got[1], naive[1])
    cubic = sl.Lattice.preset("cubic", [3, 3, 3], 1.0, 0.2, 0.1)
    assert not cubic.query_plan()["becots"] and cubic.query_plan()["becots_reason"]
    with pytest.raises(ValueError, match="layer_offset"):
        sl.becots_lattice(m, "triangle", (4, 4, 2), 0.01, layer_offset=float("nan"))
