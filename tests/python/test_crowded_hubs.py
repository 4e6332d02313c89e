"""Issue 17: crowded hubs build as valid solids of the exact volume, or refuse with a message that helps.

The sweep itself is in crowded_sweep.py (also a script); the short one runs here, the long one (at least 500
cases) with STEADY_LONG_TESTS=1 (scripts/test.sh --long).
"""
import os
import re

import numpy as np
import pytest

import crowded_sweep
import steadylattice as sl


def check_sweep(cases):
    counts, results = crowded_sweep.sweep(cases)
    failed = [(case, detail) for case, outcome, detail, _ in results if outcome == "failed"]
    assert not failed, failed
    for case, outcome, detail, _ in results:
        if outcome == "too short":
            # The refusal names the beam, its two balls and what would fit.
            assert re.search(r"beam \d+ \(balls \d+ and \d+\)", detail), detail
    return counts


def test_short_sweep_builds_every_crowded_design_or_says_what_to_change():
    counts = check_sweep(crowded_sweep.short_cases())
    # Every design of the short sweep builds (measured: 35 of 36 to the exact volume; 1 whose properties cannot be
    # computed, checked by sampling: BCC in the hull model with a screw, whose hubs' Fuses are 1e-5 off at tangent
    # contacts); before tight collars and groups of hubs, 6 were refused as too short; before the properties' Fuses
    # were retried and checked where the hubs meet, 32 were built, 34 before hubs were fused in other layouts.
    assert counts["too short"] == 0 and counts["foreign"] == 0 and counts["built"] >= 35, counts


@pytest.mark.skipif(not os.environ.get("STEADY_LONG_TESTS"), reason="set STEADY_LONG_TESTS=1")
def test_long_sweep():
    cases = crowded_sweep.long_cases()
    assert len(cases) >= 500
    check_sweep(cases)


def test_dense_octet_of_issue_17_builds_quickly_through_the_arrangement():
    """The issue's dense octet (cells of 2, node 0.4, a slight screw along W) at beam/node 0.7 failed as an
    invalid B-rep; 0.9 had no collar. Both now build one valid solid of the exact volume without a Boolean."""
    p = sl.preset("octet")
    for ratio in (0.7, 0.9):
        nodes = [(tuple(2.0 * x for x in b), 0.4) for b in p["basis"]]
        beams = [tuple(pat) + (0.4 * ratio, 0.4 * ratio) for pat in p["patterns"]]
        t = sl.Similarity.translation
        lat = sl.Lattice(nodes, beams, (3, 3, 3), t((2, 0, 0)), t((0, 2, 0)),
                         sl.Similarity.screw(0.02, (0, 0, 1), (1, 1, 0), 2.0))
        stats = {}
        props = sl.brep_properties(lat.brep(stats=stats))
        assert props["valid"] and props["solids"] == 1
        assert stats["core_hubs"] == 108 and stats["fused_cores"] == 0, stats
        assert abs(props["volume"] / lat.properties()["volume"] - 1.0) < 1e-7


@pytest.mark.parametrize("preset, node", [("octet", 0.35), ("FCC", 0.45)])
def test_hubs_joined_by_beams_too_short_for_their_collars_are_built_as_one(preset, node):
    """Beam/node 0.8 with a screw: some beams are shorter than the collars their two hubs need, even tight ones.
    Their hubs are built as one (a Fuse of their cores): one valid solid of the exact volume. The FCC's groups have
    tight collars inside the ball, through whose disks other stumps reach: the group's own volume check must not
    count what lies beyond them (it did, 2 % too much, and refused a right Fuse)."""
    lat = crowded_sweep.lattice(preset, node, 0.8, "screw", (2, 2, 2))
    stats = {}
    props = sl.brep_properties(lat.brep(stats=stats))
    assert props["valid"] and props["solids"] == 1
    assert stats["hub_groups"] > 0 and stats["grouped_hubs"] >= 2 * stats["hub_groups"], stats
    assert abs(props["volume"] / lat.properties()["volume"] - 1.0) < 1e-7


@pytest.mark.skipif(not os.environ.get("STEADY_LONG_TESTS"), reason="set STEADY_LONG_TESTS=1 (minutes: one Fuse of hundreds of hubs)")
def test_beams_as_thick_as_the_octets_nodes_build_over_hundreds_of_hubs_as_one():
    """Beams as thick as the octet's nodes: every beam is too short for its hubs' collars, and the hubs joined by
    them (all of the 5 x 5 x 4 cells') form one group of hundreds of hubs. Groups were refused over 256 hubs
    (naming the beam radii that fit) while their Fuse could not be cancelled; they are built now: one valid solid
    of the properties' volume."""
    lat = crowded_sweep.lattice("octet", 0.35, 1.0, "translation", (5, 5, 4))
    stats = {}
    props = sl.brep_properties(lat.brep(stats=stats))
    assert props["valid"] and props["solids"] == 1, props
    assert stats["hub_groups"] >= 1 and stats["grouped_hubs"] > 256, stats
    assert abs(props["volume"] / lat.properties()["volume"] - 1.0) < 1e-7


monte_carlo_volume = crowded_sweep.sampled_volume


def test_crowded_hubs_whose_stumps_meet_past_the_mid_plane_have_the_exact_volume():
    """FCC, node 0.45, beam/node 0.64, twisted taper: the stumps of crowded hubs meet beyond their beams'
    mid-planes, so hubs of neighbouring nodes overlap. properties() used to fuse those hubs with OpenCASCADE,
    which silently lost volume (5.58436 against the B-rep's 5.59323, 1.6e-3); it now moves the cuts past the
    crowded hubs' collars, as the B-rep does, and sums exact hub properties without a Boolean."""
    lat = crowded_sweep.lattice("FCC", 0.45, 0.64, "twisted taper", (2, 2, 2))
    p = lat.properties()
    assert not p["clean"] and p["moved_cuts"] > 0 and p["union_clusters"] == 0, p
    brep = sl.brep_properties(lat.brep())
    assert brep["valid"] and brep["solids"] == 1
    assert abs(p["volume"] / brep["volume"] - 1.0) < 1e-7
    mc, sigma = monte_carlo_volume(lat)
    assert abs(p["volume"] - mc) < 4 * sigma


def test_a_fuse_that_loses_volume_is_an_error_never_a_silent_figure():
    """FCC in the hull model, bent: node balls meet beams of other nodes, so the overlapping hubs must be fused.
    OpenCASCADE's Fuse of one of them returns a valid solid 9 % short of the hub's exact volume, at once and one by
    one (only the reversed order fuses it whole): whatever the Fuse gives, properties() either refuses, naming the
    hub, or reports a volume that the Monte Carlo estimate confirms."""
    lat = crowded_sweep.lattice("FCC", 0.45, None, "bend", (2, 2, 2))
    try:
        p = lat.properties()
    except (ValueError, RuntimeError) as error:
        assert re.search(r"hub of \(\d+,\d+,\d+,\d+\)", str(error)), error
        return
    mc, sigma = monte_carlo_volume(lat)
    assert abs(p["volume"] - mc) < 4 * sigma


def sampled_centroid_and_inertia(lat, n=400_000, seed=13):
    """Centroid (3,) with its standard errors, and inertia about it (3 x 3), by sampling the kernel's exact point
    membership over the lattice's box (the moments' slow twin)."""
    rng = np.random.default_rng(seed)
    centers, radii = lat.balls()
    lo, hi = (centers - radii[:, None]).min(0), (centers + radii[:, None]).max(0)
    points = lo + rng.random((n, 3)) * (hi - lo)
    inside = points[np.asarray(lat.contains(points), bool)]
    centroid = inside.mean(0)
    volume = float(np.prod(hi - lo)) * len(inside) / n
    second = volume * np.cov(inside.T)
    return centroid, inside.std(0) / np.sqrt(len(inside)), np.trace(second) * np.eye(3) - second


@pytest.mark.parametrize("preset, ratio, step", [("BCC", None, "bend"), ("BCC", 1.0, "bend")])
def test_hubs_whose_fuse_loses_a_piece_at_once_are_fused_one_by_one(preset, ratio, step):
    """Node 0.35, hubs of different nodes overlap, so properties() fuses them with OpenCASCADE. Fused all at once,
    a crowded hub whose beams touch its ball lost 10 % of its volume (BCC bent, in the hull model or with beams as
    thick as the balls: 0.401519 for 0.462302) and properties() refused
    the lattice; like the B-rep's group Fuse it now retries one by one (then with fuzzy values), every result
    checked as before. Its volume agrees with the B-rep's and with sampling, its centroid and inertia with
    sampling (brep_properties gives neither)."""
    lat = crowded_sweep.lattice(preset, 0.35, ratio, step, (2, 2, 2))
    p = lat.properties()
    assert p["union_clusters"] > 0, p
    props = sl.brep_properties(lat.brep())
    assert props["valid"] and props["solids"] == 1, props
    assert abs(props["volume"] / p["volume"] - 1) < crowded_sweep.FUSED_REFERENCE_TOLERANCE
    mc, sigma = monte_carlo_volume(lat)
    assert abs(p["volume"] - mc) < 5 * sigma
    centroid, errors, inertia = sampled_centroid_and_inertia(lat)
    assert np.all(np.abs(np.asarray(p["centroid"]) - centroid) < 5 * errors), (p["centroid"], centroid, errors)
    assert np.allclose(np.asarray(p["inertia"]), inertia, rtol=0, atol=0.01 * np.trace(inertia)), (p["inertia"], inertia)


@pytest.mark.skipif(not os.environ.get("STEADY_LONG_TESTS"), reason="set STEADY_LONG_TESTS=1")
def test_a_cluster_fuse_off_by_3e_4_is_refused_where_the_hubs_meet():
    """The long sweep's octet at node 0.45, beam/node 1.0, bent (32 hubs in one cluster): a retried Fuse of the
    cluster came out 2.7e-4 above the B-rep (7.968410 for 7.966266) and passed the check of 400,000 lines at 5.6
    sigma of 6. With 1.6 million lines and 5 sigma it is 8.3 sigma out: properties() now refuses, naming the
    cluster, or agrees with the B-rep (about 5 minutes for both)."""
    lat = crowded_sweep.lattice("octet", 0.45, 1.0, "bend", (2, 2, 2))
    brep = sl.brep_properties(lat.brep())
    assert brep["valid"] and brep["solids"] == 1, brep
    try:
        p = lat.properties()
    except RuntimeError as error:
        assert re.search(r"hub union: .*(hub|cluster of hubs) (of|around) \(\d+,\d+,\d+,\d+\)", str(error)), error
        return
    assert abs(p["volume"] / brep["volume"] - 1) < crowded_sweep.FUSED_REFERENCE_TOLERANCE, (p["volume"], brep)


def test_properties_refused_at_tangent_hubs_say_what_to_change():
    """The short sweep's BCC in the hull model with a screw: every Fuse of one hub is 1e-5 off where its beams touch
    the ball tangentially, so properties() refuses; the message names the hub and says what to change, and the same
    design with beams at 0.9 of the node is measured."""
    with pytest.raises(RuntimeError) as refusal:
        crowded_sweep.lattice("BCC", 0.35, None, "screw", (2, 2, 2)).properties()
    message = str(refusal.value)
    assert re.search(r"hub union: .*hub of \(\d+,\d+,\d+,\d+\)", message), message
    assert "touch their balls tangentially" in message and "thinner than their nodes" in message, message
    p = crowded_sweep.lattice("BCC", 0.35, 0.9, "screw", (2, 2, 2)).properties()
    assert p["volume"] > 0


def foreign_contacts(lat):
    return [i for i in lat.clean_check()["issues"] if i["kind"] != "circle_overlap"]


@pytest.mark.parametrize("preset, ratio, step", [("BCC", 0.9, "screw"), ("FCC", 1.0, "translation")])
def test_lattices_whose_elements_meet_other_nodes_build_to_the_properties_volume(preset, ratio, step):
    """Node 0.45 of the neighbour distance: balls and beams meet beams of other nodes (96 of the long sweep's 900
    cases were refused as not clean for that). The hubs of every contact are now fused as one group; the solid's
    volume matches the properties, which fuse the overlapping hubs themselves (hence FUSED_REFERENCE_TOLERANCE)."""
    lat = crowded_sweep.lattice(preset, 0.45, ratio, step, (2, 2, 2))
    assert foreign_contacts(lat)
    stats = {}
    props = sl.brep_properties(lat.brep(stats=stats))
    assert props["valid"] and props["solids"] == 1, props
    assert stats["foreign_groups"] >= 1 and stats["foreign_hubs"] > 0, stats
    reference = lat.properties()
    assert reference["union_clusters"] > 0, reference
    assert abs(props["volume"] / reference["volume"] - 1) < crowded_sweep.FUSED_REFERENCE_TOLERANCE


def test_a_lattice_whose_elements_meet_other_nodes_is_trimmed():
    """FCC, node 0.45, beam/node 0.8, a screw, 3 x 3 x 3 cells: balls meet beams of other nodes. Trimmed into the
    sweep's box with a skin, the hubs of those contacts join the band together and are fused as one group there;
    checked against sampling the lattice's membership and the box."""
    lat = crowded_sweep.lattice("FCC", 0.45, 0.8, "screw", (3, 3, 3))
    assert foreign_contacts(lat)
    stats = {}
    props = sl.brep_properties(lat.brep(body=crowded_sweep.trim_box_brep(), skin=crowded_sweep.TRIM_SKIN, stats=stats))
    assert props["valid"] and props["solids"] == 1, props
    assert stats["foreign_hubs"] > 0, stats
    estimate, sigma = crowded_sweep.sampled_trimmed_volume(lat, crowded_sweep.TRIM_SKIN)
    assert abs(props["volume"] - estimate) <= 5 * sigma, (props["volume"], estimate, sigma)


@pytest.mark.parametrize("preset, ratio, step, skin",
                         [("BCC", 1.0, "translation", 0.0), ("BCC", 1.0, "translation", 0.1), ("octet", 0.8, "screw", 0.1)])
def test_dense_lattices_with_beams_too_short_for_a_cut_are_trimmed(preset, ratio, step, skin):
    """Beams with no room for a cut between their crowded hubs' collars were refused by the trim ("too short for the
    collar"): they are never cut now, their hubs share a cluster of the band (an inside hub joined so to a crossing
    one joins the band), and the band has tight collars and groups of hubs as the whole lattice has. Checked
    against sampling the lattice's membership and the box."""
    lat = crowded_sweep.lattice(preset, 0.35, ratio, step, (3, 3, 3))
    box = crowded_sweep.trim_box_brep()
    stats = {}
    props = sl.brep_properties(lat.brep(body=box, skin=skin, stats=stats))
    assert props["valid"], props
    if skin:
        assert props["solids"] == 1, props
    assert stats["joined_band_hubs"] > 0 and stats["tight_cores"] > 0, stats
    estimate, sigma = crowded_sweep.sampled_trimmed_volume(lat, skin)
    assert abs(props["volume"] - estimate) <= 5 * sigma, (props["volume"], estimate, sigma)


def test_whole_hubs_whose_dangling_beams_have_no_room_for_a_cut_say_what_to_change():
    """Keeping hubs whole, a dangling beam ends at its cut; a beam with no room for a cut between its hubs' collars
    cannot, and the message names it and the two options that build (which then do)."""
    lat = crowded_sweep.lattice("BCC", 0.35, 1.0, "translation", (3, 3, 3))
    box = crowded_sweep.trim_box_brep()
    with pytest.raises(ValueError, match=r"dangling: beam \d+ \(balls \d+ and \d+\) has no room .*dangling='remove'"):
        lat.brep(body=box, policy="whole")
    for options in ({"policy": "whole", "dangling": "remove"}, {"policy": "clip"}):
        props = sl.brep_properties(lat.brep(body=box, **options))
        assert props["valid"] and props["solids"] == 1, (options, props)


@pytest.mark.parametrize("skin", [0.0, 0.1])
def test_open_cuts_between_collars_glue_the_interior_to_the_band(skin):
    """FCC at beam/node 0.8 (translation) in the sweep's box. Its crowded hubs' cuts lie between their collars, off
    the middle; the interior's half-beams ended halfway on the band's cut circles (their seams longer or shorter
    than their edges: unorientable faces), and the trim refused the part ("invalid near balls 52 53 54 55"). Now the
    interior is cut where the band is: one valid solid, within sampling of the lattice's membership and the box."""
    lat = crowded_sweep.lattice("FCC", 0.35, 0.8, "translation", (3, 3, 3))
    stats = {}
    props = sl.brep_properties(lat.brep(body=crowded_sweep.trim_box_brep(), skin=skin, stats=stats))
    assert props["valid"] and props["solids"] == 1, props
    assert stats["inside_hubs"] > 0 and stats["core_hubs"] > 0, stats  # interior hubs meet the band at open cuts
    estimate, sigma = crowded_sweep.sampled_trimmed_volume(lat, skin)
    assert abs(props["volume"] - estimate) <= 5 * sigma, (props["volume"], estimate, sigma)
