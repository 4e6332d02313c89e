"""The lattice as a mesh and as printer files, through the Python module: closed and oriented meshes with the
exact volume within the chord bound, files read back by readers we did not write (numpy's parse of the STL
format, lib3mf), clear errors for bad input and no file left behind."""
import math
import os
import struct

import numpy as np
import pytest

import steadylattice as sl
from conftest import cubic_lattice


def dense_octet(node=0.4, ratio=0.7, counts=(3, 3, 3)):
    """Issue 17's dense octet: cells of 2, beams `ratio` of their nodes, a slight screw along W."""
    p = sl.preset("octet")
    nodes = [(tuple(2.0 * x for x in b), node) for b in p["basis"]]
    beams = [pattern + (ratio * node, ratio * node) for pattern in p["patterns"]]
    t = sl.Similarity.translation
    return sl.Lattice(nodes, beams, counts, t((2, 0, 0)), t((0, 2, 0)),
                      sl.Similarity.screw(0.02, (0, 0, 1), (1, 1, 0), 2.0))


def edge_report(triangles):
    """(border, non-manifold, misoriented) undirected edges of an indexed triangle list."""
    directed = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]).astype(np.int64)
    lo, hi = directed.min(axis=1), directed.max(axis=1)
    key = lo * (1 << 32) + hi
    forward = directed[:, 0] < directed[:, 1]
    keys, inverse, counts = np.unique(key, return_inverse=True, return_counts=True)
    forward_counts = np.bincount(inverse, weights=forward, minlength=len(keys))
    border = int((counts == 1).sum())
    non_manifold = int((counts > 2).sum())
    misoriented = int(((counts == 2) & (forward_counts != 1)).sum())
    return border, non_manifold, misoriented


def volume_and_area(vertices, triangles):
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    cross = np.cross(b - a, c - a)
    return np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0, 0.5 * np.linalg.norm(cross, axis=1).sum()


@pytest.mark.parametrize("ratio", [0.4, 0.6, 0.8])
def test_dense_octet_mesh_is_closed_with_the_exact_volume_within_the_chord_bound(ratio):
    lat = dense_octet(ratio=ratio)
    stats = {}
    tolerance = 0.01
    vertices, triangles = lat.to_mesh(tolerance, stats=stats)
    assert vertices.dtype == np.float64 and vertices.shape[1] == 3
    assert triangles.dtype == np.uint32 and triangles.shape[1] == 3
    assert edge_report(triangles) == (0, 0, 0)
    volume, area = volume_and_area(vertices, triangles)
    exact = lat.properties()["volume"]
    assert exact - tolerance * area <= volume <= exact * (1 + 1e-9), (volume, exact, tolerance * area)
    assert stats["triangles"] == len(triangles) and stats["templates"] < stats["hubs"]


# Designs whose hubs the mesh must unite (mesh_groups.cpp): beams too short for their crowded hubs' collars (the BCC
# and the cubic cell with beams as thick as their nodes), beams of other nodes crossing (the bent FCC). The last three
# were refused: the two tessellations of each short beam's cone lay on each other (rings in step, points on the
# lattice's mirror planes), and the union folded once rounded to floats.
UNITED = [("BCC", 0.45, 0.7, "screw", 1, 14), ("FCC", 0.35, 0.9, "bend", 3, 11), ("cubic", 0.45, 1.0, "twisted taper", 1, 8),
          ("cubic", 0.45, 1.0, "translation", 1, 8), ("BCC", 0.35, 0.9, "translation", 1, 14),
          ("FCC", 0.35, 1.0, "translation", 1, 26)]


@pytest.mark.parametrize("preset, node_fraction, ratio, step, groups, hubs", UNITED)
def test_dense_lattices_whose_hubs_meet_are_meshed_closed_by_united_groups(preset, node_fraction, ratio, step, groups,
                                                                           hubs, tmp_path):
    from crowded_sweep import lattice
    lat = lattice(preset, node_fraction, ratio, step, (2, 2, 2))
    tolerance = 0.02 * node_fraction * sl.preset(preset)["neighbour_distance"]
    stats = {}
    vertices, triangles = lat.to_mesh(tolerance, stats=stats)
    assert (stats["foreign_groups"], stats["foreign_hubs"]) == (groups, hubs)
    assert edge_report(triangles) == (0, 0, 0)
    volume, area = volume_and_area(vertices, triangles)
    exact = lat.properties()["volume"]
    assert exact - tolerance * area <= volume <= exact * (1 + 1e-9), (volume, exact, tolerance * area)
    # No vertex farther than the tolerance outside the exact solid (the kernel's own distance): a vertex that the
    # union of a group makes lies on two triangles, each within the tolerance of the surface (outside it where a
    # chord spans a concave crease).
    assert lat.distance(vertices).max() <= tolerance
    # The streamed STL, parsed with numpy, is the same closed surface.
    path = str(tmp_path / "united.stl")
    lat.write_stl(path, tolerance)
    back_vertices, back_triangles = read_binary_stl(path)
    assert len(back_triangles) == len(triangles)
    assert edge_report(back_triangles) == (0, 0, 0)
    assert volume_and_area(back_vertices, back_triangles)[0] == pytest.approx(volume, rel=1e-5)


def test_tangent_short_beams_whose_caps_reach_the_other_center_mesh_within_sampling():
    # The long sweep's tapered octet at node 0.45 with beams as thick as its nodes: its collars reach to 0.0005
    # from the other node's center, where the tangent cone lies outside that ball by less than a quarter of the
    # tolerance; the mesh refused it. Its properties are refused too (tangent Fuses), so against sampling.
    from crowded_sweep import lattice, sampled_volume
    lat = lattice("octet", 0.45, 1.0, "taper", (2, 2, 2))
    tolerance = 0.02 * 0.45 * sl.preset("octet")["neighbour_distance"]
    stats = {}
    vertices, triangles = lat.to_mesh(tolerance, stats=stats)
    assert stats["short_beams"] == 108 and stats["foreign_groups"] == 1
    assert edge_report(triangles) == (0, 0, 0)
    assert lat.distance(vertices).max() <= tolerance
    volume, area = volume_and_area(vertices, triangles)
    estimate, sigma = sampled_volume(lat)
    assert estimate - 5 * sigma - tolerance * area <= volume <= estimate + 5 * sigma, (volume, estimate, sigma)


def test_the_short_crowded_sweep_meshes_every_design():
    # Issue 17's short sweep (36 designs) as meshes: each closed, within the tolerance and the chord bound of the
    # properties or of sampling. Four (the FCC with beams as thick as its nodes, the octets at 0.8, 1.0 and the hull
    # model) were refused: beams too short for their collars, whose united hubs folded once rounded to floats.
    from crowded_sweep import run_mesh_case, short_cases, sweep
    counts, results = sweep(short_cases(), run=run_mesh_case)
    assert counts["built"] + counts["sampled"] == len(results) == 36, [r for r in results if r[1] not in ("built", "sampled")]


def box_mesh(lo, hi):
    """An axis-aligned cube [lo, hi]^3 as a closed, outward triangle mesh."""
    v = np.array([[x, y, z] for z in (lo, hi) for y in (lo, hi) for x in (lo, hi)], float)
    t = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4], [2, 6, 3], [3, 6, 7],
                  [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]], np.uint32)
    return v, t


def trimmed_in_the_sweeps_box(lat, tolerance):
    """`lat` meshed trimmed into the crowded sweep's box with its skin: closed, and the sampled volume of
    lattice-in-inner-box plus skin within the chord bound. Returns the mesh's stats."""
    from crowded_sweep import TRIM_BOX, TRIM_SKIN, sampled_trimmed_volume
    corner, edge = TRIM_BOX
    stats = {}
    vertices, triangles = lat.to_mesh(tolerance, body=box_mesh(corner, corner + edge),
                                      inner=box_mesh(corner + TRIM_SKIN, corner + edge - TRIM_SKIN), stats=stats)
    assert edge_report(triangles) == (0, 0, 0)
    volume, area = volume_and_area(vertices, triangles)
    estimate, sigma = sampled_trimmed_volume(lat, TRIM_SKIN)
    assert estimate - 5 * sigma - tolerance * area <= volume <= estimate + 5 * sigma, (volume, estimate, sigma)
    return stats


def test_a_trimmed_mesh_unites_the_hubs_of_nodes_meeting_other_nodes():
    # The tapered diamond with nodes 0.45 of the neighbour distance (nodes meet nodes they share no beam with)
    # trimmed into the sweep's box with a skin.
    from crowded_sweep import lattice
    stats = trimmed_in_the_sweeps_box(lattice("diamond", 0.45, 0.5, "taper", (3, 3, 3)), 0.005)
    assert stats["foreign_groups"] > 0 and stats["crossing_hubs"] > 0


def test_a_trimmed_mesh_unites_the_hubs_of_short_beams():
    # The FCC with beams as thick as its nodes, trimmed into a box: its short beams' hubs are united as in the whole
    # mesh, then cut by the body (trimmed meshes refused short beams before).
    from crowded_sweep import lattice
    lat = lattice("FCC", 0.35, 1.0, "translation", (2, 2, 2))
    tolerance, stats = 0.02 * 0.35 * sl.preset("FCC")["neighbour_distance"], {}
    vertices, triangles = lat.to_mesh(tolerance, body=box_mesh(0.3, 1.6), stats=stats)
    assert stats["short_beams"] > 0 and stats["crossing_hubs"] > 0
    assert edge_report(triangles) == (0, 0, 0)
    volume, area = volume_and_area(vertices, triangles)
    lo, hi, n = 0.3, 1.6, 300_000
    points = lo + np.random.default_rng(5).random((n, 3)) * (hi - lo)
    f = np.asarray(lat.contains(points), bool).mean()
    estimate, sigma = f * (hi - lo) ** 3, (hi - lo) ** 3 * math.sqrt(f * (1 - f) / n)
    assert estimate - 5 * sigma - tolerance * area <= volume <= estimate + 5 * sigma, (volume, estimate, sigma)


def test_a_cancel_while_short_beams_hubs_are_united_is_a_cancel():
    # The FCC with beams as thick as its nodes: progress stays at 0.39 while its group of 26 hubs is united (about
    # 5 s). A cancel there came out as the short beams' refusal (a ValueError ending "(cancelled)").
    from crowded_sweep import lattice
    lat = lattice("FCC", 0.35, 1.0, "translation", (2, 2, 2))
    fractions = []

    def progress(fraction):
        fractions.append(fraction)
        return fraction < 0.39

    with pytest.raises(sl.Cancelled):
        lat.to_mesh(0.02 * 0.35 * sl.preset("FCC")["neighbour_distance"], progress=progress)
    assert fractions[-1] == pytest.approx(0.39, abs=0.005)


@pytest.mark.parametrize("ratio, step", [(1.0, "taper"), (None, "twisted taper")])
def test_short_beams_united_hubs_cut_by_the_body_mesh_closed(ratio, step):
    # The tapered cubic cell with beams as thick as its nodes (and its hull model, twisted), trimmed with a skin:
    # the body's cut through its united hubs folded once rounded to floats, and the mesh was refused naming the
    # first short beam. The band's repair (its short edges and needles collapsed where it folds) now meshes them.
    from crowded_sweep import lattice
    stats = trimmed_in_the_sweeps_box(lattice("cubic", 0.45, ratio, step, (3, 3, 3)), 0.009)
    assert stats["short_beams"] > 0 and stats["float_removed_triangles"] > 0


def read_binary_stl(path):
    """A binary STL parsed with numpy from the format's definition (not with our reader)."""
    with open(path, "rb") as f:
        data = f.read()
    (count,) = struct.unpack_from("<I", data, 80)
    assert len(data) == 84 + 50 * count
    records = np.frombuffer(data, dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]),
                            offset=84, count=count)
    corners = records["v"].reshape(-1, 3)
    unique, index = np.unique(corners, axis=0, return_inverse=True)
    return unique.astype(np.float64), index.reshape(-1, 3).astype(np.uint32)


def test_stl_streamed_from_the_lattice_reads_back_closed(tmp_path):
    lat = dense_octet(ratio=0.6)
    path = str(tmp_path / "octet.stl")
    stats = {}
    lat.write_stl(path, 0.01, name="dense octet", stats=stats)
    vertices, triangles = read_binary_stl(path)
    assert len(triangles) == stats["triangles"]
    assert edge_report(triangles) == (0, 0, 0)
    v_mesh, t_mesh = lat.to_mesh(0.01)
    assert volume_and_area(vertices, triangles)[0] == pytest.approx(volume_and_area(v_mesh, t_mesh)[0], rel=1e-5)
    assert not os.path.exists(path + ".partial")


def test_3mf_mesh_and_beam_lattice_read_back_by_lib3mf(tmp_path):
    lat = dense_octet(ratio=0.6, counts=(2, 2, 2))
    mesh_path, beams_path = str(tmp_path / "mesh.3mf"), str(tmp_path / "beams.3mf")
    lat.write_3mf(mesh_path, 0.02, name="octet", unit="millimeter")
    back = sl.read_3mf(mesh_path)
    assert back["warnings"] == [] and back["unit"] == "millimeter"
    (obj,) = back["objects"]
    assert obj["name"] == "octet" and edge_report(obj["triangles"]) == (0, 0, 0)
    stats = {}
    lat.write_3mf(beams_path, beam_lattice=True, stats=stats)
    back = sl.read_3mf(beams_path)
    (obj,) = back["objects"]
    a, b = lat.beams()[:2]  # arrays of the beams' end balls
    assert len(obj["beams"]) == len(a) == stats["beams_written"]
    assert [(v1, v2) for v1, v2, _, _ in obj["beams"]] == list(zip(a.tolist(), b.tolist()))
    radii = np.array([(b[2], b[3]) for b in obj["beams"]])
    assert np.allclose(radii, 0.6 * 0.4, rtol=1e-7)


def test_bad_tolerance_path_unit_and_cancel_leave_nothing_behind(tmp_path):
    lat = cubic_lattice()
    for tolerance in (0.0, -0.01, float("nan"), 1.0):
        with pytest.raises(ValueError, match="tolerance"):
            lat.to_mesh(tolerance)
    with pytest.raises(ValueError, match="path"):
        lat.write_stl(str(tmp_path / "missing" / "a.stl"), 0.01)
    with pytest.raises(ValueError, match="unit"):
        lat.write_3mf(str(tmp_path / "a.3mf"), 0.01, unit="furlong")
    with pytest.raises(ValueError, match="tolerance"):
        lat.write_3mf(str(tmp_path / "a.3mf"))
    # progress is reported about every 0.1 s: a mesh that takes longer than that, cancelled at its first report
    path = str(tmp_path / "cancelled.stl")
    with pytest.raises(sl.Cancelled):
        dense_octet(ratio=0.6, counts=(6, 6, 6)).write_stl(path, 0.002, progress=lambda fraction: False)
    assert os.listdir(tmp_path) == []


def test_a_stats_argument_that_is_not_a_dict_is_refused_before_any_work(tmp_path):
    """A wrong stats argument used to be found only when the stats were filled, after the whole mesh (minutes at
    10^6 beams) had been built and written; now every output refuses it before starting: no progress reported,
    no file written."""
    lat = cubic_lattice()
    calls = []

    def progress(fraction):
        calls.append(fraction)
        return True

    attempts = [
        lambda: lat.to_mesh(0.01, progress=progress, stats=[]),
        lambda: lat.write_stl(str(tmp_path / "a.stl"), 0.01, progress=progress, stats="x"),
        lambda: lat.write_3mf(str(tmp_path / "a.3mf"), 0.01, progress=progress, stats=1),
        lambda: lat.write_3mf(str(tmp_path / "b.3mf"), beam_lattice=True, progress=progress, stats=()),
        lambda: lat.write_slices(str(tmp_path), 0.1, 0.05, progress=progress, stats=[]),
    ]
    for attempt in attempts:
        with pytest.raises(ValueError, match="stats: expected a dict"):
            attempt()
    assert calls == [] and os.listdir(tmp_path) == []
