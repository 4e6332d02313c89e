"""Connectors of constant-radius lattices from the module: families of a BeCOTS lattice placed onto every member's
beam directions (brute force from balls() and beams()), a template's volume against Monte Carlo membership of
Ball ∩ ExtendedHub(sleeve) − ExtendedHub(hole) (numpy), a cubic grid's families, the rods' cut list, STEP files read
back by OpenCASCADE, and bad input."""
import math
import os
import tempfile

import numpy as np
import pytest

import steadylattice as sl


def becots_triangle(nu=4, nv=3):
    m = sl.BecotsMap((0, 0, 0), (0.1, 1, 0.2), (1.3, 1.2, -0.3), (1, 0, 0.1))
    return sl.becots_lattice(m, sl.becots_connectivity("triangle"), (nu, nv, 1), 0.01)


def grid(n):
    t = sl.Similarity.translation
    beams = [(0, 1, 0, 0, 0), (0, 0, 1, 0, 0), (0, 0, 0, 1, 0)]
    return sl.Lattice([((0, 0, 0), 0.2)], beams, (n, n, n), t((1, 0, 0)), t((0, 1, 0)), t((0, 0, 1)))


def shortest_beam(lat):
    centers, _ = lat.balls()
    a, b, _, _ = lat.beams()
    return float(np.min(np.linalg.norm(centers[b] - centers[a], axis=1)))


def fitting_connectors(lat, rod_radius, sleeve=1.6):
    low, high = lat.connector_reach_range(rod_radius, sleeve=sleeve)
    assert low < high
    return lat.connectors(rod_radius, sleeve=sleeve, reach=0.5 * (low + high))


def beam_directions(lat):
    """Per ball the unit directions of its beams (brute force over all beams)."""
    centers, _ = lat.balls()
    a, b, _, _ = lat.beams()
    out = [[] for _ in range(len(centers))]
    for i, j in zip(a, b):
        d = centers[j] - centers[i]
        d /= np.linalg.norm(d)
        out[i].append(d)
        out[j].append(-d)
    return centers, out


def test_becots_families_are_placed_onto_every_members_beam_directions():
    lat = becots_triangle()
    c = fitting_connectors(lat, shortest_beam(lat) / 10)
    centers, directions = beam_directions(lat)
    families = c.families
    assert sum(f["count"] for f in families) == lat.ball_count
    assert len(families) <= 9  # inner, four edges, four corners
    for f in families:
        assert f["valid"] and f["volume"] > 0
        for ball, P in zip(f["balls"], f["placements"]):
            R, t = P[:3, :3], P[:3, 3]
            assert np.allclose(R @ R.T, np.eye(3), atol=1e-12) and abs(np.linalg.det(R) - 1) < 1e-12  # a rotation
            assert np.allclose(t, centers[ball], atol=1e-12)
            placed = f["directions"] @ R.T
            world = np.array(directions[ball])
            # Each placed direction is one of the member's beam directions, and they pair off one to one.
            distance = np.linalg.norm(placed[:, None, :] - world[None, :, :], axis=2)
            assert distance.min(axis=1).max() < 1e-8
            assert sorted(distance.argmin(axis=1)) == list(range(len(world)))
    assert (c.family_of_ball >= 0).all()


def in_capsules(p, directions, radius, bulge):
    inside = np.linalg.norm(p, axis=1) <= radius * (1 + bulge)
    for d in directions:
        along = p @ d
        radial = np.linalg.norm(p - along[:, None] * d[None, :], axis=1)
        inside |= (along >= 0) & (radial <= radius)
    return inside


def test_template_volume_matches_monte_carlo_membership():
    lat = becots_triangle()
    rho = shortest_beam(lat) / 10
    c = fitting_connectors(lat, rho)
    low, high = c.reach_range
    reach = 0.5 * (low + high)
    rng = np.random.default_rng(3)
    families = c.families
    k = max(range(len(families)), key=lambda k: len(families[k]["directions"]))  # the inner nodes' degree-6 one
    inner = families[k]
    d = np.asarray(inner["directions"])
    n = 1_000_000
    half = reach * rho
    p = rng.uniform(-half, half, (n, 3))
    # Beams run past the ball (plan_connectors checks), so each capsule is a half-infinite cylinder within it.
    inside = (np.linalg.norm(p, axis=1) <= half) & in_capsules(p, d, 1.6 * rho, 0.05) & ~in_capsules(p, d, rho, 0.05)
    fraction = inside.mean()
    box = (2 * half) ** 3
    sigma = box * math.sqrt(fraction * (1 - fraction) / n)
    assert abs(inner["volume"] - box * fraction) < 4 * sigma
    props = sl.brep_properties(c.brep(k))
    assert props["valid"] and props["solids"] == 1
    assert props["volume"] == pytest.approx(inner["volume"], rel=1e-9)


def test_cubic_grid_has_corner_edge_face_and_inner_families():
    c = grid(4).connectors(0.08)
    found = sorted((len(f["directions"]), f["count"]) for f in c.families)
    assert found == [(3, 8), (4, 24), (5, 24), (6, 8)]
    cut = c.cut_list
    assert len(cut) == 1 and cut[0]["count"] == 3 * 4 * 4 * 3  # every rod: 1 - 2 rho (ends rho cot 45 deg inside)
    assert cut[0]["length"] == pytest.approx(1 - 2 * 0.08, abs=1e-12)
    rods = c.rods
    assert np.allclose(np.linalg.norm(rods["ends"] - rods["starts"], axis=1), rods["lengths"], atol=1e-12)
    # Visible between the connectors: 1 - 2 sqrt(reach^2 - hole^2) rho.
    assert np.allclose(rods["exposed"], 1 - 2 * math.sqrt(2.5 ** 2 - 1) * 0.08, atol=1e-12)


def test_step_assembly_and_family_files_read_back():
    lat = becots_triangle(3, 3)
    c = fitting_connectors(lat, shortest_beam(lat) / 10)
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "connectors.step")
        c.write_step(path)
        parts = sl.read_step(path)
        families = c.families
        assert len(parts) == lat.ball_count + lat.beam_count
        for f in families:
            copies = [p for p in parts if p["name"] == f["name"]]
            assert len(copies) == f["count"]
            for p in copies:
                assert p["valid"] and p["solids"] == 1
                assert p["volume"] == pytest.approx(f["volume"], rel=1e-6)
        rho = shortest_beam(lat) / 10
        for entry in c.cut_list:
            copies = [p for p in parts if p["name"] == entry["name"]]
            assert len(copies) == entry["count"]
            for p in copies:
                assert p["volume"] == pytest.approx(math.pi * rho * rho * entry["length"], rel=1e-6)
        one = os.path.join(folder, "family.step")
        c.write_family_step(0, one)
        (part,) = sl.read_step(one)
        assert part["name"] == "Connector_1" and part["valid"] and part["solids"] == 1
        assert part["volume"] == pytest.approx(families[0]["volume"], rel=1e-6)


def test_bad_input_names_the_parameter():
    lat = grid(2)
    for kwargs, name in [
        (dict(rod_radius=0.0), "rod_radius"),
        (dict(rod_radius=float("nan")), "rod_radius"),
        (dict(rod_radius=0.05, sleeve=1.0), "sleeve"),
        (dict(rod_radius=0.05, hole=0.5), "hole"),
        (dict(rod_radius=0.05, reach=1.0), "reach"),
        (dict(rod_radius=0.05, core_bulge=0.0), "core_bulge"),
        (dict(rod_radius=0.05, angle_tolerance=-1.0), "angle_tolerance"),
    ]:
        with pytest.raises(ValueError, match="^" + name + ":"):
            lat.connectors(**kwargs)
    # Beams of length 1 with rods of radius 0.3: the sleeves (reach 2.5) would run 0.69 along each, more than half.
    with pytest.raises(ValueError, match=r"reach: beam \d+ \(balls \d+ and \d+, length 1\) is too short"):
        lat.connectors(0.3)
    with pytest.raises(ValueError, match="family"):
        lat.connectors(0.05).write_family_step(7, os.path.join(tempfile.gettempdir(), "never.step"))
