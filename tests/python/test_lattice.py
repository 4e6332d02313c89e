"""The Lattice API of the module: listings against iteration, stable indices, controls, files, bad input."""
import json
import math
import re

import numpy as np
import pytest

import steadylattice as sl
from conftest import cubic_lattice


def graded():
    nodes = [((0, 0, 0), 0.2), ((0.5, 0.5, 0.5), 0.15)]
    beams = [(0, 1, 0, 0, 0), (0, 0, 1, 0, 0), (0, 0, 0, 1, 0), (0, 0, 0, 0, 1), (1, 1, 1, 1, 0, 0.05, 0.04)]
    U = sl.Similarity.swirl(0.05, (0, 0, 1), (0, -20, 0), 1.01)
    V = sl.Similarity.screw(0.03, (1, 0, 0), (0, 0, 5), 1.0)
    W = sl.Similarity.swirl(-0.02, (0.2, 1, 0.1), (3, 3, -10), 0.99)
    G = sl.Similarity.rotation(0.4, (1, 1, 0), (1, 2, 3))
    return sl.Lattice(nodes, beams, (6, 5, 4), U, V, W, G, omitted=[(1, 1, 1, 0), (5, 4, 3, 1)])


def test_balls_match_iterated_similarities():
    lat = graded()
    centers, radii = lat.balls()
    assert centers.shape == (lat.ball_count, 3) and radii.shape == (lat.ball_count,)
    U, V, W, G = lat.U, lat.V, lat.W, lat.G
    for index in range(lat.ball_count):
        i, j, k, n = lat.ball_id(index)
        p = np.array(lat.nodes[n][0], dtype=float)
        r = lat.nodes[n][1]
        for _ in range(i):
            p = U.apply(p)
        for _ in range(j):
            p = V.apply(p)
        for _ in range(k):
            p = W.apply(p)
        p = G.apply(p)
        assert np.abs(centers[index] - p).max() < 1e-11
        assert radii[index] == pytest.approx(r * U.scale ** i * V.scale ** j * W.scale ** k, rel=1e-13)


def test_beams_index_into_balls_and_skip_omissions():
    lat = graded()
    centers, radii = lat.balls()
    a, b, ra, rb = lat.beams()
    assert a.dtype == np.int64 and len(a) == lat.beam_count
    assert a.min() >= 0 and b.max() < lat.ball_count
    omitted = {lat.ball_index(*o) for o in [(1, 1, 1, 0), (5, 4, 3, 1)]}
    assert omitted == {-1}
    # every beam's end balls are where the pattern says
    for index in range(lat.beam_count):
        i, j, k, p = lat.beam_id(index)
        n1, di, dj, dk, n2 = lat.beam_patterns[p][:5]
        assert a[index] == lat.ball_index(i, j, k, n1)
        assert b[index] == lat.ball_index(i + di, j + dj, k + dk, n2)
        ca, ra_, cb, rb_ = lat.beam(i, j, k, p)
        assert np.allclose(ca, centers[a[index]]) and np.allclose(cb, centers[b[index]])
        assert ra_ == pytest.approx(ra[index]) and rb_ == pytest.approx(rb[index])
    # hull model beams carry their balls' radii; explicit ones their own
    hull = [q for q in range(lat.beam_count) if lat.beam_id(q)[3] == 0]
    assert np.allclose(ra[hull], radii[a[hull]])
    explicit = [q for q in range(lat.beam_count) if lat.beam_id(q)[3] == 4]
    assert np.all(ra[explicit] < radii[a[explicit]])


def test_beam_count_matches_brute_force():
    lat = cubic_lattice((5, 4, 3))
    assert lat.ball_count == 60
    assert lat.beam_count == 4 * 4 * 3 + 5 * 3 * 3 + 5 * 4 * 2


def test_interpolating_and_frames_controls():
    nodes = [((0, 0, 0), 0.1)]
    beams = [(0, 1, 0, 0, 0)]
    total = sl.Similarity.swirl(1.0, (0, 0, 1), (-3, 0, 0), 2.0)
    lat = sl.Lattice.interpolating(nodes, beams, (5, 1, 1), total, sl.Similarity(), sl.Similarity())
    assert lat.group(4, 0, 0).approx_equal(total, 1e-12)
    assert lat.U.power(4).approx_equal(total, 1e-12)
    base = ((1, 1, 1), (1, 0, 0), (0, 1, 0), (0, 0, 1))
    end_u = ((10, 1, 1), (0, 2, 0), (-2, 0, 0), (0, 0, 2))
    end_v = ((1, 5, 1), (1, 0, 0), (0, 1, 0), (0, 0, 1))
    end_w = ((1, 1, 4), (0, 0, 1), (0, 1, 0), (-1, 0, 0))
    lf = sl.Lattice.from_frames(nodes, beams, (4, 3, 2), base, end_u, end_v, end_w)
    assert np.allclose(lf.ball(3, 0, 0, 0)[0], (10, 1, 1))
    assert lf.ball(3, 0, 0, 0)[1] == pytest.approx(0.2)
    assert np.allclose(lf.ball(0, 2, 0, 0)[0], (1, 5, 1))
    assert np.allclose(lf.ball(0, 0, 1, 0)[0], (1, 1, 4))


def test_json_round_trip_is_exact():
    lat = graded()
    text = lat.to_json()
    again = sl.Lattice.from_json(text)
    assert again.to_json() == text
    c1, r1 = lat.balls()
    c2, r2 = again.balls()
    assert np.array_equal(c1, c2) and np.array_equal(r1, r2)
    doc = json.loads(text)
    assert doc["format"] == "steady-lattice" and doc["version"] == sl.FORMAT_VERSION


@pytest.mark.parametrize("edit, field", [
    (lambda d: d["nodes"][0].update(radius=-1), "nodes[0].radius"),
    (lambda d: d["beams"][0].update(to=9), "beams[0].to"),
    (lambda d: d.update(counts=[0, 1, 1]), "counts.u"),
    (lambda d: d.update(version=99), "version"),
    (lambda d: d.pop("counts"), "counts: missing field"),
    (lambda d: d["layout"]["U"].update(type="shear"), "layout.U.type"),
    (lambda d: d["layout"].update(kind="spiral"), "layout.kind"),
    (lambda d: d["layout"].update(order="VWU"), "layout.order: unknown field"),
])
def test_bad_files_are_refused_naming_the_field(edit, field):
    doc = json.loads(graded().to_json())
    edit(doc)
    with pytest.raises(ValueError, match=field.replace("[", r"\[").replace("]", r"\]").replace(".", r"\.")):
        sl.Lattice.from_json(json.dumps(doc))


def test_nan_in_a_file_is_refused():
    text = graded().to_json().replace('"radius": 0.2', '"radius": NaN', 1)
    with pytest.raises(ValueError, match="not valid JSON"):
        sl.Lattice.from_json(text)


T = sl.Similarity.translation((1, 0, 0))


@pytest.mark.parametrize("args, field", [
    (([((0, 0, 0), -0.1)], [], (1, 1, 1), T, T, T), "nodes[0].radius"),
    (([((0, 0, math.nan), 0.1)], [], (1, 1, 1), T, T, T), "nodes[0].center"),
    (([((0, 0, 0), 0.1)], [], (0, 1, 1), T, T, T), "counts.u"),
    (([((0, 0, 0), 0.1)], [], (1, 1), T, T, T), "counts"),
    (([((0, 0, 0), 0.1)], [(0, 1, 0, 0, 3)], (2, 1, 1), T, T, T), "beams[0].to"),
    (([((0, 0, 0), 0.1)], [(0, 1, 0, 0)], (2, 1, 1), T, T, T), "beams[0]"),
    (([((0, 0, 0), 0.1)], [(0, 1, 0, 0, 0, 0.2, 0.05)], (2, 1, 1), T, T, T), "beams[0].radii[0]"),
    (([((0, 0, 0), 0.1)], [], (2, 1, 1), T, None, T), "V"),
    (([((0, 0, 0), 0.1)], [], (2, 1, 1), T, "not a similarity", T), "V"),
    (([((0, 0, 0), 0.1)], [], (1000, 1, 1), sl.Similarity.dilation(10.0), T, T), "U, V, W"),
])
def test_bad_lattices_are_value_errors_naming_the_field(args, field):
    with pytest.raises(ValueError, match=field.replace("[", r"\[").replace("]", r"\]").replace(".", r"\.")):
        sl.Lattice(*args)


def test_a_lattice_too_large_to_list_is_a_memory_error():
    lat = cubic_lattice((100000, 100000, 10000))
    assert lat.ball_count == 10 ** 14
    with pytest.raises(MemoryError, match="balls"):
        lat.balls()
    with pytest.raises(MemoryError, match="beams"):
        lat.beams()
    # single elements stay O(1)
    assert np.allclose(lat.ball(99999, 99999, 9999, 0)[0], (99999, 99999, 9999))


def test_out_of_range_indices():
    lat = cubic_lattice()
    assert lat.ball_index(9, 0, 0, 0) == -1
    with pytest.raises(ValueError, match="ball index"):
        lat.ball_id(lat.ball_count)
    with pytest.raises(ValueError):
        lat.ball(9, 0, 0, 0)


def test_unreadable_json_shapes_are_refused_naming_the_field():
    # Nodes, beams or frames that are not JSON objects (issue 16, repro 08), integers beyond int64, and an
    # indentation that only makes the file grow (repro 13) are refused with ValueError naming the field.
    base = json.loads(graded().to_json())
    for key, bad, field in [("nodes", [5], "nodes[0]: expected an object"),
                            ("beams", [[0, 1, 0, 0, 0]], "beams[0]: expected an object"),
                            ("counts", [2 ** 64 - 1, 1, 1], "counts.u: integer out of range")]:
        doc = dict(base)
        doc[key] = bad
        with pytest.raises(ValueError, match=re.escape(field)):
            sl.Lattice.from_json(json.dumps(doc))
    doc = json.loads(json.dumps(base))
    doc["layout"]["placement"] = {"type": "frames", "from": [1], "to": [2]}
    with pytest.raises(ValueError, match=r"layout\.placement\.(from|to): expected an object"):
        sl.Lattice.from_json(json.dumps(doc))
    for indent in (-2, 65, 1000000):
        with pytest.raises(ValueError, match="indent"):
            graded().to_json(indent=indent)
    assert graded().to_json(indent=64).startswith("{")
    with pytest.raises(ValueError, match="max_reported: must be >= 0"):
        graded().clean_check(max_reported=-1)
