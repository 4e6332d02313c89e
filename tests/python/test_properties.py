"""Integral properties, the clean check and density targeting from Python."""
import math

import numpy as np
import pytest

import steadylattice as sl
from conftest import random_similarity


def graded_bcc(n=4, bend=0.002, grade=1.003):
    t = sl.Similarity.translation
    u = t((1, 0, 0)) * sl.Similarity.swirl(bend, (0, 1, 0), (0, 0, 0), grade)
    nodes = [((0, 0, 0), 0.2), ((0.5, 0.5, 0.5), 0.18)]
    beams = [(0, 1, 0, 0, 0, 0.06, 0.06), (0, 0, 1, 0, 0, 0.06, 0.06), (0, 0, 0, 1, 0, 0.06, 0.06),
             (0, 0, 0, 0, 1, 0.07, 0.06), (1, 1, 0, 0, 0, 0.06, 0.07), (1, 1, 1, 1, 0, 0.06, 0.07)]
    return sl.Lattice(nodes, beams, (n, n, n), u, t((0, 1, 0)), t((0, 0, 1)))


def test_properties_dict():
    p = graded_bcc().properties()
    assert set(p) >= {"volume", "area", "centroid", "inertia", "clean_verified"}
    assert p["centroid"].shape == (3,) and p["inertia"].shape == (3, 3)
    assert p["volume"] > 0 and p["area"] > 0 and p["clean_verified"]
    inertia = p["inertia"]
    assert np.allclose(inertia, inertia.T, atol=1e-12 * np.abs(inertia).max())
    assert np.all(np.linalg.eigvalsh(inertia) > 0)


def test_balls_only_lattice_matches_a_numpy_sum_over_balls(rng):
    # Independent of the kernel's sums: parallel-axis sum over the balls listed by balls().
    for kind in range(6):
        lat = sl.Lattice([((0, 0, 0), 0.3), ((0.4, 0.1, 0.2), 0.2)], [], (4, 3, 5), random_similarity(rng, kind),
                         random_similarity(rng, kind + 1), random_similarity(rng, kind + 2),
                         G=random_similarity(rng, 5), omitted=[(1, 1, 1, 0), (3, 2, 4, 1)])
        centers, radii = lat.balls()
        mass = 4.0 / 3.0 * math.pi * radii ** 3
        volume = mass.sum()
        centroid = (mass[:, None] * centers).sum(axis=0) / volume
        d = centers - centroid
        inertia = np.zeros((3, 3))
        for m, r, v in zip(mass, radii, d):
            inertia += 0.4 * m * r * r * np.eye(3) + m * (v @ v * np.eye(3) - np.outer(v, v))
        p = lat.properties(check_clean=False)
        assert p["volume"] == pytest.approx(volume, rel=1e-12)
        assert np.allclose(p["centroid"], centroid, atol=1e-10 * np.abs(centers).max())
        assert np.allclose(p["inertia"], inertia, rtol=0, atol=1e-10 * np.abs(inertia).max())
        assert p["area"] == pytest.approx((4 * math.pi * radii ** 2).sum(), rel=1e-12)


def test_properties_match_the_brute_force_sum(rng):
    t = sl.Similarity.translation
    for trial in range(3):
        u = t((1, 0, 0)) * random_similarity(rng, 4).power(0.05)
        lat = sl.Lattice([((0, 0, 0), 0.15), ((0.5, 0.5, 0.5), 0.15)],
                         [(0, 1, 0, 0, 0, 0.08, 0.07), (0, 0, 1, 0, 0), (0, 0, 0, 0, 1, 0.1, 0.1), (1, 1, 1, 1, 0)],
                         (3, 3, 3), u, t((0, 1, 0)), t((0, 0, 1)), omitted=[(1, 1, 1, 1)])
        fast, brute = lat.properties(check_clean=False), lat.properties_brute_force()
        assert fast["volume"] == pytest.approx(brute["volume"], rel=1e-9)
        assert fast["area"] == pytest.approx(brute["area"], rel=1e-9)
        assert np.allclose(fast["centroid"], brute["centroid"], atol=1e-9)
        assert np.allclose(fast["inertia"], brute["inertia"], atol=1e-9 * np.abs(brute["inertia"]).max())


def test_non_clean_lattice_is_reported_and_united():
    t = sl.Similarity.translation
    lat = sl.Lattice([((0, 0, 0), 0.4), ((0.5, 0.5, 0), 0.4)], [(0, 1, 0, 0, 0, 0.1, 0.1), (1, 1, 0, 0, 1, 0.1, 0.1)],
                     (3, 2, 1), t((1, 0, 0)), t((0, 1, 0)), t((0, 0, 1)))
    report = lat.hub_overlap_report()
    assert report["verified"] and not report["clean"] and report["overlap_count"] > 0
    a, b, pieces = report["overlaps"][0]
    assert len(a) == 4 and len(b) == 4 and isinstance(pieces, str)
    with pytest.raises(ValueError, match="not clean"):
        lat.properties(union_overlaps=False)
    p = lat.properties()
    assert not p["clean"] and p["overlap_count"] == report["overlap_count"]
    assert "(0,0,0,0) and (0,0,0,1)" in p["overlap_description"]
    assert p["union_hubs"] == 12 and p["union_clusters"] == 1
    summed = lat.properties(check_clean=False)
    # Monte Carlo with the kernel's exact point membership: the union is right, the plain sum is not.
    rng = np.random.default_rng(5)
    centers, radii = lat.balls()
    lo, hi = (centers - radii[:, None]).min(0), (centers + radii[:, None]).max(0)
    n = 400_000
    points = lo + rng.random((n, 3)) * (hi - lo)
    inside = np.asarray(lat.contains(points), bool)
    box, f = np.prod(hi - lo), inside.mean()
    mc, sigma = f * box, np.prod(hi - lo) * math.sqrt(f * (1 - f) / n)
    assert abs(p["volume"] - mc) < 4 * sigma
    assert abs(summed["volume"] - mc) > 10 * sigma
    assert np.allclose(p["centroid"], points[inside].mean(0), atol=0.01)


def test_scale_radii_reaches_the_target_volume():
    lat = graded_bcc()
    v = lat.properties()["volume"]
    scaled = lat.scale_radii_for_volume(0.7 * v)
    assert isinstance(scaled, sl.Lattice)
    assert scaled.properties()["volume"] == pytest.approx(0.7 * v, rel=1e-9)
    solution = lat.radius_scale_for_volume(0.7 * v)
    assert solution["scale"] == pytest.approx(scaled.nodes[0][1] / lat.nodes[0][1], rel=1e-14)
    assert solution["evaluations"] <= 15
    envelope = lat.cell_envelope_volume()
    dense = lat.scale_radii_for_density(0.05)
    assert dense.properties()["volume"] == pytest.approx(0.05 * envelope, rel=1e-9)
    heavy = lat.scale_radii_for_mass(2.0, density=4.0)
    assert heavy.properties()["volume"] == pytest.approx(0.5, rel=1e-9)


def test_bad_input_names_the_parameter():
    lat = graded_bcc(3)
    with pytest.raises(ValueError, match="target_volume"):
        lat.scale_radii_for_volume(-1.0)
    with pytest.raises(ValueError, match="target_volume"):
        lat.scale_radii_for_volume(1e9)
    with pytest.raises(ValueError, match="relative_density"):
        lat.scale_radii_for_density(2.0)
    with pytest.raises(ValueError, match="tolerance"):
        lat.properties(tolerance=0.0)
    with pytest.raises(ValueError, match="scale"):
        lat.with_radius_scale(-2.0)


def test_progress_can_cancel_the_clean_check():
    calls = []

    def report(fraction):
        calls.append(fraction)
        return False

    lat = graded_bcc(30)
    with pytest.raises(sl.Cancelled):
        lat.hub_overlap_report(progress=report)
    assert calls
