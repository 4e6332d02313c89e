"""Issue 17's robustness sweep: crowded hubs of every preset, node radius, beam/node ratio and kind of step.

Each case builds the lattice's B-rep (no body) and checks it against the closed-form properties: one valid solid
per connected lattice, volume equal to the exact one to 1e-7 relative (5e-7 where the properties fuse overlapping
hubs themselves, see FUSED_REFERENCE_TOLERANCE). A case either passes, builds a lattice
whose properties cannot be computed (then checked against sampling its membership), is refused because elements of
different hubs meet (the clean check's business, not a hub's), is refused because a beam is too short for the
collars of its two crowded hubs (the message must name the beam), or fails.

`python3 crowded_sweep.py [--long] [--only SPEC] [--trim | --trim-cylinder | --mesh | --trim --mesh |
--properties]` prints every case and the counts (--only: a part of the sweep, see `only`; --trim: each design
trimmed into a box with a skin instead, checked against sampling; --trim-cylinder: into a cylinder without a skin,
likewise; --mesh: each design as a mesh, run_mesh_case; both: each design as a trimmed
mesh, run_trim_mesh_case; --properties: only the exact properties, run_properties_case, the census of those
refused);
test_crowded_hubs.py runs the short sweep, test_mesh.py the short mesh sweep.
"""
import functools
import itertools
import math
import os
import sys
import time

import numpy as np

import steadylattice as sl

VOLUME_TOLERANCE = 1e-7
# Where hubs of different nodes overlap, properties() is no closed form either: it fuses the overlapping hubs with
# OpenCASCADE and integrates the result, and the approximated intersection curves of two different Fuses disagree
# by about 1e-7. Measured on the octet at node 0.45, beam/node 0.7, translation (32 hubs in one cluster): the B-rep
# 5.6e-8 below and the properties 5.8e-8 above a brute-force Fuse of all 48 balls and 192 cylinders (all three
# integrated to 1e-9). Against such a reference the tolerance is 5e-7.
FUSED_REFERENCE_TOLERANCE = 5e-7
PRESETS = ["cubic", "BCC", "FCC", "octet", "diamond", "Kelvin"]


def steps(kind):
    """U, V, W steps of a unit cell for each kind of steady step (bends and tapers about far centres)."""
    t = sl.Similarity.translation
    u, v, w = t((1, 0, 0)), t((0, 1, 0)), t((0, 0, 1))
    if kind == "screw":
        w = sl.Similarity.screw(0.03, (0, 0, 1), (0.5, 0.5, 0), 1.0)
    elif kind == "bend":
        u = sl.Similarity.swirl(-0.05, (0, 0, 1), (0, -20, 0), 1.0)
    elif kind == "taper":
        u = sl.Similarity.dilation(1.05, (-20, 0.5, 0.5))
    elif kind == "twisted taper":
        u = sl.Similarity.swirl(0.03, (1, 0, 0), (-20, 0.5, 0.5), 1.05)
    return u, v, w


def lattice(preset, node_fraction, ratio, step, counts):
    """node_fraction: node radius over the preset's neighbour distance; ratio: beam radius over node radius, or
    None for the hull model (beams tangent to their balls)."""
    p = sl.preset(preset)
    node = node_fraction * p["neighbour_distance"]
    nodes = [(tuple(b), node) for b in p["basis"]]
    beams = [tuple(pat) + ((node * ratio, node * ratio) if ratio is not None else ()) for pat in p["patterns"]]
    return sl.Lattice(nodes, beams, counts, *steps(step))


@functools.lru_cache(maxsize=None)
def design_properties(preset, node_fraction, ratio, step, counts):
    """lat.properties() of a sweep design, computed once per process: the B-rep and the mesh sweeps of one test run
    share it (the short sweep's octet at beam/node 1.0, bent, fuses 32 hubs in about 2 minutes). A refusal is not
    kept and is raised again on the next call."""
    return lattice(preset, node_fraction, ratio, step, counts).properties()


def run_case(preset, node_fraction, ratio, step, counts=(2, 2, 2)):
    """(outcome, detail, seconds): outcome is 'built' (the properties' volume to 1e-7, or 5e-7 where they are
    fused), 'sampled' (built, but the lattice's properties cannot be computed: its volume within 5 sigma of
    sampling), 'foreign', 'too short' or 'failed'."""
    lat = lattice(preset, node_fraction, ratio, step, counts)
    start = time.perf_counter()
    try:
        stats = {}
        text = lat.brep(stats=stats)
    except ValueError as error:
        message = str(error)
        seconds = time.perf_counter() - start
        if "is not clean" in message:
            return "foreign", message[:120], seconds
        if "too short for the collar" in message and "beam " in message:
            return "too short", message[:160], seconds
        return "failed", message[:300], seconds
    except RuntimeError as error:
        return "failed", str(error)[:300], time.perf_counter() - start
    seconds = time.perf_counter() - start
    props = sl.brep_properties(text)
    detail = "%d cores (%d distinct, %d fused, %d tight), %d hubs in %d groups, %d meeting others in %d groups" % (
        stats["core_hubs"], stats["distinct_cores"], stats["fused_cores"], stats["tight_cores"],
        stats["grouped_hubs"], stats["hub_groups"], stats["foreign_hubs"], stats["foreign_groups"])
    try:
        reference = design_properties(preset, node_fraction, ratio, step, counts)
    except (ValueError, RuntimeError) as error:
        # properties() fuses overlapping hubs of other nodes with OpenCASCADE and refuses when that Fuse loses
        # volume (the hull model's tangent cones): the part is then checked against sampling its membership.
        estimate, sigma = sampled_volume(lat)
        detail += ", no exact volume (%s), sampled %.4f +- %.4f, B-rep %.4f" % (
            str(error)[:60], estimate, sigma, props["volume"])
        if not props["valid"] or props["solids"] != 1 or not abs(props["volume"] - estimate) <= 5 * sigma:
            return "failed", "valid %s, %d solids, %s" % (props["valid"], props["solids"], detail), seconds
        return "sampled", detail, seconds
    error = abs(props["volume"] / reference["volume"] - 1.0)
    tolerance = VOLUME_TOLERANCE
    if reference["union_clusters"]:
        tolerance = FUSED_REFERENCE_TOLERANCE
        detail += ", properties fused %d hubs" % reference["union_hubs"]
    detail += ", volume error %.1e" % error
    if not props["valid"] or props["solids"] != 1 or not error <= tolerance:
        return "failed", "valid %s, %d solids, %s" % (props["valid"], props["solids"], detail), seconds
    return "built", detail, seconds


def sampled_volume(lat, n=400_000, seed=11):
    """Volume by sampling the kernel's exact point membership over the lattice's box, and its standard error."""
    rng = np.random.default_rng(seed)
    centers, radii = lat.balls()
    lo, hi = (centers - radii[:, None]).min(0), (centers + radii[:, None]).max(0)
    points = lo + rng.random((n, 3)) * (hi - lo)
    f = np.asarray(lat.contains(points), bool).mean()
    box = float(np.prod(hi - lo))
    return f * box, box * math.sqrt(f * (1 - f) / n)


def short_cases():
    """About thirty cases across presets, ratios and steps (the default test run)."""
    ratios = [0.3, 0.5, 0.64, 0.8, 1.0, None]
    kinds = ["translation", "screw", "bend", "taper", "twisted taper"]
    cases = []
    for k, (preset, ratio) in enumerate(itertools.product(PRESETS, ratios)):
        cases.append((preset, 0.35, ratio, kinds[k % len(kinds)]))
    return cases


def long_cases():
    """At least 500 cases: every preset, three node radii, eight ratios and the hull model, five kinds of step."""
    ratios = [0.3, 0.4, 0.5, 0.6, 0.64, 0.7, 0.8, 0.9, 1.0, None]
    kinds = ["translation", "screw", "bend", "taper", "twisted taper"]
    return list(itertools.product(PRESETS, [0.25, 0.35, 0.45], ratios, kinds))


# The trimmed sweep's body (tests/python/data/dense_box.brep): a box across the middle of 3 x 3 x 3 unit cells.
TRIM_BOX = (0.325, 1.75)  # corner (each coordinate) and edge
TRIM_SKIN = 0.1


def trim_box_brep():
    """TRIM_BOX as BREP text (written by data/make_bodies.py)."""
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "dense_box.brep")) as f:
        return f.read()


def sampled_trimmed_volume(lat, skin, n=400_000, seed=7):
    """Volume of the lattice inside the box's inner offset, united with the box's skin, by sampling the kernel's
    point membership and the box's own inequalities; and its standard error."""
    rng = np.random.default_rng(seed)
    corner, edge = TRIM_BOX
    points = corner + rng.random((n, 3)) * edge
    inner = np.all((points > corner + skin) & (points < corner + edge - skin), axis=1)
    f = (~inner | np.asarray(lat.contains(points), bool)).mean()
    return f * edge ** 3, edge ** 3 * math.sqrt(f * (1 - f) / n)


def trimmed_brep(lat, body, skin, stats):
    """(text, refusal, seconds): the lattice trimmed into `body` as BREP text and no refusal, or the refusal's
    message and its outcome ('foreign', 'too short' or 'failed')."""
    start = time.perf_counter()
    try:
        text = lat.brep(body=body, skin=skin, stats=stats)
    except (ValueError, RuntimeError) as error:
        message = str(error)
        outcome = "foreign" if "is not clean" in message else "too short" if "too short" in message else "failed"
        return message[:300], outcome, time.perf_counter() - start
    return text, None, time.perf_counter() - start


def run_trim_case(preset, node_fraction, ratio, step):
    """The same designs (3 x 3 x 3 cells) trimmed into TRIM_BOX with a skin of TRIM_SKIN: 'built' (one valid solid,
    volume within 5 sigma of sampling), 'foreign', 'too short' or 'failed'."""
    lat = lattice(preset, node_fraction, ratio, step, (3, 3, 3))
    stats = {}
    text, refusal, seconds = trimmed_brep(lat, trim_box_brep(), TRIM_SKIN, stats)
    if refusal:
        return refusal, text, seconds
    props = sl.brep_properties(text)
    estimate, sigma = sampled_trimmed_volume(lat, TRIM_SKIN)
    detail = "%d cores (%d tight), %d hubs in %d groups, %d meeting others in %d groups, %d joined to the band, " \
             "%d clusters (%d fuzzy), volume %.5f, sampled %.5f +- %.5f" % (
                 stats["core_hubs"], stats["tight_cores"], stats["grouped_hubs"], stats["hub_groups"],
                 stats["foreign_hubs"], stats["foreign_groups"], stats["joined_band_hubs"], stats["band_clusters"],
                 stats["fuzzy_clusters"], props["volume"], estimate, sigma)
    if not props["valid"] or props["solids"] != 1 or not abs(props["volume"] - estimate) <= 5 * sigma:
        return "failed", "valid %s, %d solids, %s" % (props["valid"], props["solids"], detail), seconds
    return "built", detail, seconds


# The cylinder trim's body (tests/python/data/dense_cylinder.brep): along z through the middle of the 3 x 3 x 3
# cells, its wall across the crowded hubs (there, thin bands of cone between two hubs' tight collars were refused).
TRIM_CYLINDER = ((1.25, 1.25), 1.05, (-1.0, 3.5))  # axis, radius, z range


def sampled_cylinder_volume(lat, n=400_000, seed=7):
    """Volume of the lattice inside TRIM_CYLINDER by sampling the kernel's point membership, and its standard error."""
    rng = np.random.default_rng(seed)
    (cx, cy), radius, (z0, z1) = TRIM_CYLINDER
    centers, radii = lat.balls()
    lo = np.maximum((centers - radii[:, None]).min(0), (cx - radius, cy - radius, z0))
    hi = np.minimum((centers + radii[:, None]).max(0), (cx + radius, cy + radius, z1))
    points = lo + rng.random((n, 3)) * (hi - lo)
    inside = np.hypot(points[:, 0] - cx, points[:, 1] - cy) <= radius
    hits = np.zeros(n, bool)
    hits[inside] = np.asarray(lat.contains(points[inside]), bool)
    box = float(np.prod(hi - lo))
    f = hits.mean()
    return f * box, box * math.sqrt(f * (1 - f) / n)


def run_cylinder_trim_case(preset, node_fraction, ratio, step):
    """The designs (3 x 3 x 3 cells) trimmed into TRIM_CYLINDER without a skin: 'built' (one valid solid, volume
    within 5 sigma of sampling), 'foreign', 'too short' or 'failed'."""
    lat = lattice(preset, node_fraction, ratio, step, (3, 3, 3))
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "dense_cylinder.brep")) as f:
        body = f.read()
    stats = {}
    text, refusal, seconds = trimmed_brep(lat, body, 0.0, stats)
    if refusal:
        return refusal, text, seconds
    props = sl.brep_properties(text)
    estimate, sigma = sampled_cylinder_volume(lat)
    # The wall can cut a beam's chord off its hubs: the part may be several solids.
    detail = "%d solids, %d clusters (%d retried: %d fuzzy, %d with bands merged), volume %.5f, sampled %.5f +- " \
             "%.5f" % (props["solids"], stats["band_clusters"], stats["retried_clusters"], stats["fuzzy_clusters"],
                       stats["merged_clusters"], props["volume"], estimate, sigma)
    if not props["valid"] or not abs(props["volume"] - estimate) <= 5 * sigma:
        return "failed", "valid %s, %s" % (props["valid"], detail), seconds
    return "built", detail, seconds


def mesh_refusal(error, start):
    """(outcome, detail, seconds) of a mesh that was refused: 'too short' when the refusal names a beam too short
    for its hubs' collars, else 'failed'."""
    message = str(error)
    named = isinstance(error, ValueError) and "too short for the collars" in message and "beam " in message
    return "too short" if named else "failed", message[:300], time.perf_counter() - start


def run_mesh_case(preset, node_fraction, ratio, step):
    """The same designs (2 x 2 x 2 cells) as a mesh at a tolerance of 0.02 node radii: 'built' (closed and
    oriented, no vertex farther than the tolerance outside the solid, the properties' volume within the chord
    bound), 'sampled' (the same against sampling where the properties cannot be computed), 'too short' (refused
    naming a beam too short for its hubs' collars) or 'failed'."""
    from test_mesh import edge_report, volume_and_area
    lat = lattice(preset, node_fraction, ratio, step, (2, 2, 2))
    tolerance = 0.02 * node_fraction * sl.preset(preset)["neighbour_distance"]
    start = time.perf_counter()
    stats = {}
    try:
        vertices, triangles = lat.to_mesh(tolerance, stats=stats)
    except (ValueError, RuntimeError) as error:
        return mesh_refusal(error, start)
    seconds = time.perf_counter() - start
    volume, area = volume_and_area(vertices, triangles)
    outside = float(lat.distance(vertices).max())
    detail = "%d triangles, %d hubs in %d groups (%d short beams, %.2f s), volume %.5f, bound %.5f, outside %.1e" % (
        len(triangles), stats["foreign_hubs"], stats["foreign_groups"], stats["short_beams"], stats["group_seconds"],
        volume, tolerance * area, outside)
    closed = edge_report(triangles) == (0, 0, 0) and outside <= tolerance
    try:
        exact = design_properties(preset, node_fraction, ratio, step, (2, 2, 2))["volume"]
    except (ValueError, RuntimeError):
        estimate, sigma = sampled_volume(lat)
        detail += ", sampled %.5f +- %.5f" % (estimate, sigma)
        inside = estimate - 5 * sigma - tolerance * area <= volume <= estimate + 5 * sigma
        return ("sampled" if closed and inside else "failed"), detail, seconds
    detail += ", exact %.5f" % exact
    inside = exact - tolerance * area <= volume <= exact * (1 + 1e-9)
    return ("built" if closed and inside else "failed"), detail, seconds


def run_trim_mesh_case(preset, node_fraction, ratio, step):
    """The designs as trimmed meshes (3 x 3 x 3 cells in TRIM_BOX with a skin of TRIM_SKIN, tolerance 0.02 of the
    node radius): 'built' (closed and oriented, volume within 5 sigma of sampling and the chord bound), 'too short'
    (refused naming a beam too short for its hubs' collars) or 'failed'."""
    from test_mesh import box_mesh, edge_report, volume_and_area
    lat = lattice(preset, node_fraction, ratio, step, (3, 3, 3))
    corner, edge = TRIM_BOX
    tolerance = 0.02 * node_fraction * sl.preset(preset)["neighbour_distance"]
    start = time.perf_counter()
    stats = {}
    try:
        vertices, triangles = lat.to_mesh(tolerance, body=box_mesh(corner, corner + edge),
                                          inner=box_mesh(corner + TRIM_SKIN, corner + edge - TRIM_SKIN), stats=stats)
    except (ValueError, RuntimeError) as error:
        return mesh_refusal(error, start)
    seconds = time.perf_counter() - start
    volume, area = volume_and_area(vertices, triangles)
    estimate, sigma = sampled_trimmed_volume(lat, TRIM_SKIN)
    detail = "%d triangles, %d short beams, volume %.5f, sampled %.5f +- %.5f, bound %.5f" % (
        len(triangles), stats["short_beams"], volume, estimate, sigma, tolerance * area)
    closed = edge_report(triangles) == (0, 0, 0)
    inside = estimate - 5 * sigma - tolerance * area <= volume <= estimate + 5 * sigma
    return ("built" if closed and inside else "failed"), detail, seconds


def run_properties_case(preset, node_fraction, ratio, step):
    """The same designs' properties alone (no B-rep): 'exact' (a sum over hubs), 'fused' (overlapping hubs fused
    by OpenCASCADE) or 'refused' (the Fuse failed its checks: the B-rep sweep then falls back to sampling)."""
    lat = lattice(preset, node_fraction, ratio, step, (2, 2, 2))
    start = time.perf_counter()
    try:
        p = lat.properties()
    except (ValueError, RuntimeError) as error:
        return "refused", str(error)[:300], time.perf_counter() - start
    seconds = time.perf_counter() - start
    if p["union_clusters"]:
        return "fused", "volume %.6f, %d hubs in %d clusters, error %.1e" % (
            p["volume"], p["union_hubs"], p["union_clusters"], p["union_error"]), seconds
    return "exact", "volume %.6f" % p["volume"], seconds


def sweep(cases, out=sys.stdout, run=run_case):
    counts = {"built": 0, "sampled": 0, "foreign": 0, "too short": 0, "failed": 0}
    results = []
    for case in cases:
        outcome, detail, seconds = run(*case)
        counts[outcome] = counts.get(outcome, 0) + 1
        results.append((case, outcome, detail, seconds))
        print("%-8s node %.2f ratio %-5s %-13s %-9s %6.2f s  %s" % (
            case[0], case[1], "hull" if case[2] is None else case[2], case[3], outcome, seconds, detail),
            file=out, flush=True)
    print("cases %d: %s" % (len(cases), ", ".join("%s %d" % kv for kv in counts.items())), file=out, flush=True)
    return counts, results


def only(cases, spec):
    """The cases matching `spec`, "key=v1,v2;key=..." with keys preset, node, ratio ("hull" for the model) and
    step: e.g. "node=0.45;ratio=0.8,0.9,1.0,hull" (the long sweep's densest designs)."""
    for part in filter(None, spec.split(";")):
        key, _, values = part.partition("=")
        keys = ["preset", "node", "ratio", "step"]
        if key not in keys:
            raise SystemExit("--only: %r is not one of %s" % (key, ", ".join(keys)))
        index = keys.index(key)
        wanted = set(values.split(","))
        cases = [c for c in cases if ("hull" if c[index] is None else str(c[index])) in wanted]
    return cases


if __name__ == "__main__":
    trim, mesh = "--trim" in sys.argv, "--mesh" in sys.argv
    chosen = long_cases() if "--long" in sys.argv else short_cases()
    if "--only" in sys.argv:
        chosen = only(chosen, sys.argv[sys.argv.index("--only") + 1])
    sweep(chosen,
          run=run_cylinder_trim_case if "--trim-cylinder" in sys.argv else
          run_trim_mesh_case if trim and mesh else run_trim_case if trim else run_mesh_case if mesh else
          run_properties_case if "--properties" in sys.argv else run_case)
