"""The trim policy 'bridge' on conformal BeCOTS stacks: a cylinder filled with stacked polar discs (rings that follow
its wall), without and with a skin, and a cone filled with stacked sheets rolled onto it. Each part: one valid solid;
every kept hub whole inside the wall (the inner wall with a skin); one bridge per kept hub that lost a neighbour,
toward its nearest wall point (checked against the body's closed form); the volume against Monte Carlo membership
in the bridged lattice (brute force) inside the wall, plus the skin in closed form. Then rerouted bridges, on
crowded lattices in a box where some nearest routes are blocked, checked by brute force."""
import math
import os

import numpy as np
import pytest

import steadylattice as sl
from brute_force import hull_gap, inside_lattice

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")


def body(name):
    with open(os.path.join(DATA, name)) as f:
        return f.read()


def stacked(apex, a, nu, nv, layers, dilation, radius, layer_raise):
    """Triangle-connectivity BeCOTS stack about the z axis through `apex`: nu groups around (a ring open by two
    spacings: a whole turn would make corners coincide), nv rings dilated by `dilation` in all, the layers joined."""
    m = sl.BecotsMap.from_field(apex, (0, 0, 1), a, complex(0, 2 * math.pi * nu / (nu + 1)),
                                complex(math.log(dilation), 0))
    nodes, beams = sl.becots_connectivity("triangle")
    beams = list(beams) + [(n, 0, 0, 1, n) for n in range(len(nodes))]
    return sl.becots_lattice(m, (nodes, beams), (nu, nv, layers), radius, layer_raise=layer_raise, beam_ratio=0.5)


class Cylinder:
    """The body of bridge_cylinder.brep: radius 20 about the z axis, z from -1 to 21."""
    brep, lo, hi = "bridge_cylinder.brep", (-20, -20, -1), (20, 20, 21)

    @staticmethod
    def distance(p):
        return np.minimum(20.0 - np.hypot(p[..., 0], p[..., 1]), np.minimum(p[..., 2] + 1.0, 21.0 - p[..., 2]))

    @staticmethod
    def skin_volume(t):
        return math.pi * (20.0 ** 2 * 22.0 - (20.0 - t) ** 2 * (22.0 - 2 * t))

    @staticmethod
    def lattice():
        # discs in the plane z = 1 and raised along the axis; the sixth ring reaches the wall and is dropped
        return stacked((0, 0, 1.0), (7.0, 0, 1.0), 16, 6, 3, 24.0 / 7.0, 0.35, 2.5)


class Cone:
    """The body of bridge_cone.brep: radius 22 at z = 0 to 8 at z = 28 about the z axis (apex at z = 44)."""
    brep, lo, hi = "bridge_cone.brep", (-22, -22, 0), (22, 22, 28)
    cos_a = 1.0 / math.hypot(1.0, 0.5)

    @classmethod
    def distance(cls, p):
        lateral = (22.0 - 0.5 * p[..., 2] - np.hypot(p[..., 0], p[..., 1])) * cls.cos_a
        return np.minimum(lateral, np.minimum(p[..., 2], 28.0 - p[..., 2]))

    @staticmethod
    def lattice():
        # sheets on the cone's own half-angle, 0.6 down its axis (0.27 inside the wall: the outer layer crosses
        # it and is dropped), rings growing down past the base, layers 3 further down each
        apex = 44.0 - 0.6
        return stacked((0, 0, apex), ((apex - 24.0) * 0.5, 0, 24.0), 20, 5, 3, 2.6, 0.35, -3.0)


@pytest.mark.parametrize("shape, skin", [(Cylinder, 0.0), (Cone, 0.0), (Cylinder, 0.8)],
                         ids=["cylinder", "cone", "cylinder with skin"])
def test_conformal_fill_with_bridges(shape, skin):
    lat, text = shape.lattice(), body(shape.brep)
    stats = {}
    props = sl.brep_properties(lat.brep(text, "bridge", skin=skin, stats=stats))
    assert props["valid"], props["report"]
    assert props["solids"] == 1
    assert not stats["union_through_pores"]
    plan = lat.bridge_plan(text, skin)
    centers, radii = lat.balls()
    kept = plan["kept"]

    def wall_distance(p):
        return shape.distance(p) - skin

    # kept hubs: whole inside the wall; every hub whose ball reaches it: dropped
    assert np.all(wall_distance(centers[kept]) > radii[kept])
    assert not (set(np.nonzero(wall_distance(centers) < radii)[0].tolist()) & set(kept.tolist()))
    # hubs that lost a neighbour, counted here: one bridge each, none blocked
    is_kept = np.zeros(lat.ball_count, dtype=bool)
    is_kept[kept] = True
    a, b, _, _ = lat.beams()
    lost = set(a[is_kept[a] & ~is_kept[b]].tolist()) | set(b[is_kept[b] & ~is_kept[a]].tolist())
    assert len(lost) > 0
    assert plan["lost_neighbour_hubs"] == len(lost) == stats["lost_neighbour_hubs"]
    assert sorted(br["hub"] for br in plan["bridges"]) == sorted(lost)
    assert plan["blocked"] == [] and stats["blocked_bridges"] == 0
    assert stats["bridges"] == len(lost) and stats["kept_hubs"] == len(kept)
    assert stats["rerouted_bridges"] == 0 and all(br["route"] == "nearest" for br in plan["bridges"])
    for br in plan["bridges"]:
        c = centers[br["hub"]]
        assert abs(wall_distance(br["wall"])) < 1e-6  # on the wall
        assert abs(np.linalg.norm(br["wall"] - c) - wall_distance(c)) < 1e-6  # the nearest point
    # the part is the bridged lattice inside the wall, and the skin
    bridged = Bridged(plan)
    rng = np.random.default_rng(15)
    samples = 200000
    points = rng.uniform(shape.lo, shape.hi, size=(samples, 3))
    points = points[wall_distance(points) >= 0.0]
    box = float(np.prod(np.subtract(shape.hi, shape.lo)))
    p = inside_lattice(points, bridged).sum() / samples
    estimate = box * p + (shape.skin_volume(skin) if skin else 0.0)
    sigma = box * math.sqrt(p * (1 - p) / samples)
    assert abs(props["volume"] - estimate) < 4 * sigma, (props["volume"], estimate, sigma)


class Bridged:
    """The bridged lattice of bridge_plan() with the balls() / beams() a Lattice has, for the brute force."""

    def __init__(self, plan):
        self._balls, self._beams = plan["balls"], plan["beams"]

    def balls(self):
        return self._balls

    def beams(self):
        return self._beams


def test_bridge_policy_errors_name_the_policy():
    lat = Cylinder.lattice()
    with pytest.raises(ValueError, match="policy.*'bridge'"):
        lat.brep(body(Cylinder.brep), "bridges")
    with pytest.raises(ValueError, match="body"):
        lat.bridge_plan("not BREP")


def prism(sides=512, radius=20.0, z0=-1.0, z1=21.0):
    """A closed, outward mesh of the regular prism inscribed in the cylinder of bridge_cylinder.brep."""
    t = 2 * math.pi * np.arange(sides) / sides
    ring = np.column_stack([radius * np.cos(t), radius * np.sin(t)])
    vertices = np.vstack([np.column_stack([ring, np.full(sides, z0)]), np.column_stack([ring, np.full(sides, z1)]),
                          [(0, 0, z0), (0, 0, z1)]])
    k, n = np.arange(sides), (np.arange(sides) + 1) % sides
    bottom, top = 2 * sides, 2 * sides + 1
    triangles = np.vstack([np.column_stack([k, n, n + sides]), np.column_stack([k, n + sides, k + sides]),
                           np.column_stack([np.full(sides, bottom), n, k]),
                           np.column_stack([np.full(sides, top), k + sides, n + sides])])
    return vertices, triangles


def test_bridged_mesh_is_closed_with_the_bridged_volume():
    """to_mesh(policy='bridge'): the bridged lattice clipped by the body's mesh (a 512-gon prism in the cylinder):
    closed and consistently oriented, the bridge counts of the B-rep, and the volume against Monte Carlo in the
    prism within 4 sigma plus the chord bound (tolerance x area), and against the B-rep part within the chord
    bound."""
    from test_mesh import edge_report, volume_and_area
    lat, text = Cylinder.lattice(), body(Cylinder.brep)
    tolerance, stats = 0.01, {}
    vertices, triangles = lat.to_mesh(tolerance, body=prism(), policy="bridge", brep=text, stats=stats)
    assert edge_report(triangles) == (0, 0, 0)
    plan = lat.bridge_plan(text)
    assert stats["bridges"] == stats["lost_neighbour_hubs"] == len(plan["bridges"]) > 0
    assert stats["blocked_bridges"] == 0 and stats["kept_hubs"] == len(plan["kept"])
    assert stats["rerouted_bridges"] == 0
    volume, area = volume_and_area(vertices, triangles)
    rng = np.random.default_rng(16)
    samples = 200000
    points = rng.uniform(Cylinder.lo, Cylinder.hi, size=(samples, 3))
    angles = 2 * math.pi * np.arange(512) / 512
    normals = np.column_stack([np.cos(angles + math.pi / 512), np.sin(angles + math.pi / 512)])
    inside = np.all(points[:, :2] @ normals.T <= 20.0 * math.cos(math.pi / 512), axis=1)
    points = points[inside & (points[:, 2] >= -1.0) & (points[:, 2] <= 21.0)]
    box = float(np.prod(np.subtract(Cylinder.hi, Cylinder.lo)))
    p = inside_lattice(points, Bridged(plan)).sum() / samples
    estimate, sigma = box * p, box * math.sqrt(p * (1 - p) / samples)
    assert abs(volume - estimate) < 4 * sigma + tolerance * area, (volume, estimate, sigma, tolerance * area)
    # the B-rep part of the same policy in the exact cylinder (the prism lies within 4e-4 of it): within the chord
    # bound of the mesh, a sharper check than the Monte Carlo one
    exact = sl.brep_properties(lat.brep(text, "bridge"))["volume"]
    assert abs(volume - exact) < tolerance * area, (volume, exact, tolerance * area)


def test_bridged_mesh_arguments_are_checked():
    lat, text = Cylinder.lattice(), body(Cylinder.brep)
    with pytest.raises(ValueError, match="brep"):
        lat.to_mesh(0.01, body=prism(), policy="bridge")
    with pytest.raises(ValueError, match="policy.*whole"):
        lat.to_mesh(0.01, body=prism(), policy="whole", brep=text)
    with pytest.raises(ValueError, match="policy.*body"):
        lat.to_mesh(0.01, policy="bridge", brep=text)
    with pytest.raises(ValueError, match="skin"):
        lat.to_mesh(0.01, body=prism(), policy="bridge", brep=text, skin=0.5)


# ---- rerouted bridges ---------------------------------------------------------------------------------------------

BOX_LO, BOX_HI = np.full(3, -0.4), np.full(3, 2.6)  # box.brep


def box_distance(p, skin=0.0):
    """Signed distance to the wall of box.brep (positive inside), or with a skin to its inner wall (the box shrunk
    by the skin), in closed form."""
    p, lo, hi = np.asarray(p, dtype=float), BOX_LO + skin, BOX_HI - skin
    inside = np.minimum(p - lo, hi - p).min(axis=-1)
    outside = np.linalg.norm(np.maximum(0.0, np.maximum(lo - p, p - hi)), axis=-1)
    return np.where(inside >= 0.0, inside, -outside)


def box_nearest(p, skin=0.0):
    """The nearest point of the wall of box.brep (shrunk by the skin) to the inside point p, and the wall's outward
    normal there."""
    lo, hi = BOX_LO + skin, BOX_HI - skin
    gaps = np.concatenate([p - lo, hi - p])
    k = int(np.argmin(gaps))
    q, n = np.array(p, dtype=float), np.zeros(3)
    q[k % 3] = lo[k % 3] if k < 3 else hi[k % 3]
    n[k % 3] = -1.0 if k < 3 else 1.0
    return q, n


def crowded_lattice(seed):
    """A cubic lattice of spacing 0.5 with face and body diagonals (beams 0.05, nodes 0.14), turned at random and
    centred in box.brep: routes to the nearest wall point often pass a kept neighbour."""
    rng = np.random.default_rng(seed)
    turn, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    step, n, r = 0.5, 9, 0.05
    origin = np.full(3, 1.1) - turn @ np.full(3, step * (n - 1) / 2) + rng.uniform(-0.2, 0.2, 3)
    beams = [(0, 1, 0, 0, 0, r, r), (0, 0, 1, 0, 0, r, r), (0, 0, 0, 1, 0, r, r), (0, 1, 1, 0, 0, r, r),
             (0, 0, 1, 1, 0, r, r), (0, 1, 0, 1, 0, r, r), (0, 1, 1, 1, 0, r, r)]
    t = sl.Similarity.translation
    return sl.Lattice([(tuple(origin), 0.14)], beams, (n, n, n), *(t(tuple(step * turn[:, k])) for k in range(3)))


def route_gaps(c, end, radius, e0, e1, r0, r1):
    """The least gaps between capsules on [c, end] of radius `radius` and the hulls of the balls (e0, r0),
    (e1, r1) (M pairs; a ball when e0 = e1), negative where they overlap: the hull's signed gap (hull_gap) from the
    axis point c + s (end - c), less the radius, is convex in s; sampled, then a ternary search in the bracket
    about the least sample."""
    def gap(s):
        return hull_gap(c + s[..., None] * (end - c), e0, r0, e1, r1, iterations=40) - radius

    samples = np.linspace(0.0, 1.0, 33)
    g = gap(np.repeat(samples[:, None], len(e0), axis=1))  # (33, M)
    i = np.argmin(g, axis=0)
    lo, hi = samples[np.maximum(i - 1, 0)], samples[np.minimum(i + 1, len(samples) - 1)]
    for _ in range(40):
        m1, m2 = lo + (hi - lo) / 3, hi - (hi - lo) / 3
        left = gap(m1) < gap(m2)
        lo, hi = np.where(left, lo, m1), np.where(left, m2, hi)
    return np.minimum(g.min(axis=0), gap(0.5 * (lo + hi)))


def route_clearances(lat, kept, routes, bridges):
    """For each route (hub, far node, radius) from its hub's node, the least gap to every kept element not of that
    hub and every bridge in `bridges` of another hub, by brute force (inf when none is near); elements farther than
    the route's half length plus their own from its midpoint are skipped (they cannot come nearer than that)."""
    centers, radii = lat.balls()
    a, b, ra, rb = lat.beams()
    is_kept = np.zeros(lat.ball_count, dtype=bool)
    is_kept[kept] = True
    beams = is_kept[a] & is_kept[b]
    e0 = np.vstack([centers[kept], centers[a[beams]], np.reshape([centers[br["hub"]] for br in bridges], (-1, 3))])
    e1 = np.vstack([centers[kept], centers[b[beams]], np.reshape([br["end"] for br in bridges], (-1, 3))])
    r0 = np.concatenate([radii[kept], ra[beams], [br["radius"] for br in bridges]])
    r1 = np.concatenate([radii[kept], rb[beams], [br["radius"] for br in bridges]])
    hub_a = np.concatenate([kept, a[beams], [br["hub"] for br in bridges]])
    hub_b = np.concatenate([kept, b[beams], [br["hub"] for br in bridges]])
    pairs, cs, ends, rs = [], [], [], []
    for k, (hub, end, radius) in enumerate(routes):
        c = centers[hub]
        mid, half = 0.5 * (c + end), 0.5 * np.linalg.norm(end - c)
        near = (np.linalg.norm(0.5 * (e0 + e1) - mid, axis=1) - half - 0.5 * np.linalg.norm(e1 - e0, axis=1) -
                radius - np.maximum(r0, r1) <= 0.0) & (hub_a != hub) & (hub_b != hub)
        for j in np.nonzero(near)[0]:
            pairs.append((k, j))
            cs.append(c)
            ends.append(end)
            rs.append(radius)
    least = np.full(len(routes), np.inf)
    if pairs:
        k, j = np.array(pairs).T
        gaps = route_gaps(np.array(cs), np.array(ends), np.array(rs), e0[j], e1[j], r0[j], r1[j])
        np.minimum.at(least, k, gaps)
    return least


@pytest.mark.parametrize("seed, skin", [(0, 0.0), (1, 0.0), (2, 0.0), (3, 0.0), (0, 0.2)])
def test_rerouted_bridges_are_clear_and_end_on_the_wall(seed, skin):
    """Turned crowded lattices in box.brep (and one with a skin, bridged to its inner wall), where some routes to
    the nearest wall point are blocked: every bridge, nearest or rerouted, is clear of every kept element of another
    hub and of every other bridge (by brute force, independently of the kernel's capsule tests), starts at its hub,
    meets the wall (closed form, 1e-6) on the line to its far node, whose ball lies outside the wall; nearest ones
    end at the nearest point, rerouted ones are no shorter, and their nearest route was not clear. Every hub that
    lost a neighbour is bridged once or blocked; the plan is the same when asked again."""
    lat, text = crowded_lattice(seed), body("box.brep")
    plan = lat.bridge_plan(text, skin)
    centers, radii = lat.balls()
    bridges, kept = plan["bridges"], plan["kept"]
    routes = [br["route"] for br in bridges]
    assert routes == sorted(routes)  # the nearest ones first
    again = lat.bridge_plan(text, skin)["bridges"]
    assert [(br["hub"], br["route"], tuple(br["wall"])) for br in again] == \
        [(br["hub"], br["route"], tuple(br["wall"])) for br in bridges]
    assert routes.count("rerouted") > 0, "the case no longer exercises rerouting"
    hubs = [br["hub"] for br in bridges] + list(plan["blocked"])
    assert len(hubs) == len(set(hubs)) == plan["lost_neighbour_hubs"]
    nearest_made = [br for br in bridges if br["route"] == "nearest"]
    assert np.all(route_clearances(lat, kept, [(br["hub"], br["end"], br["radius"]) for br in bridges], bridges) > 0)
    for br in bridges:
        c, wall, end, r = centers[br["hub"]], br["wall"], br["end"], br["radius"]
        assert abs(box_distance(wall, skin)) < 1e-6
        assert np.linalg.norm(np.cross(wall - c, end - c)) < 1e-9 * np.linalg.norm(end - c) ** 2 + 1e-12
        assert box_distance(end, skin) <= -r + 1e-9  # the far node's ball clear of the wall
        if br["route"] == "nearest":
            assert abs(np.linalg.norm(wall - c) - box_distance(c, skin)) < 1e-6
        else:
            assert np.linalg.norm(wall - c) >= box_distance(c, skin) - 1e-9
            # its nearest route met a kept element or a nearest bridge of a hub before it
            q, n = box_nearest(c, skin)
            earlier = [other for other in nearest_made if other["hub"] < br["hub"]]
            assert route_clearances(lat, kept, [(br["hub"], q + 1.5 * r * n, r)], earlier)[0] < 1e-9


@pytest.mark.parametrize("skin", [0.0, 0.2], ids=["no skin", "skin 0.2"])
def test_rerouted_bridges_make_one_valid_solid(skin):
    """The first crowded lattice trimmed with its rerouted bridges, without and with a skin: one valid solid with
    the plan's counts, whose volume agrees with Monte Carlo membership in the bridged lattice inside the (inner)
    wall, plus the skin in closed form; without a skin the mesh path reports the same counts."""
    lat, text = crowded_lattice(0), body("box.brep")
    stats, messages = {}, []
    props = sl.brep_properties(lat.brep(text, "bridge", skin=skin, stats=stats, log=messages.append))
    assert props["valid"], props["report"]
    assert props["solids"] == 1
    plan = lat.bridge_plan(text, skin)
    rerouted = sum(br["route"] == "rerouted" for br in plan["bridges"])
    assert stats["rerouted_bridges"] == rerouted > 0
    assert stats["bridges"] == len(plan["bridges"]) and stats["blocked_bridges"] == len(plan["blocked"]) == 0
    assert sum("rerouted" in m for m in messages) == rerouted
    rng = np.random.default_rng(18)
    samples = 200000
    points = rng.uniform(BOX_LO, BOX_HI, size=(samples, 3))
    points = points[box_distance(points, skin) >= 0.0]
    box = float(np.prod(BOX_HI - BOX_LO))
    p = inside_lattice(points, Bridged(plan)).sum() / samples
    estimate = box * p + box - float(np.prod(BOX_HI - BOX_LO - 2 * skin))
    sigma = box * math.sqrt(p * (1 - p) / samples)
    assert abs(props["volume"] - estimate) < 4 * sigma, (props["volume"], estimate, sigma)
    print("skin %g: %d bridges, %d rerouted, volume %.5f, Monte Carlo %.5f +- %.5f"
          % (skin, stats["bridges"], rerouted, props["volume"], estimate, sigma))
    if skin:
        return
    vertices = np.array([[x, y, z] for x in (-0.4, 2.6) for y in (-0.4, 2.6) for z in (-0.4, 2.6)])
    triangles = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1], [2, 3, 7], [2, 7, 6],
                          [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    mesh_stats = {}
    lat.to_mesh(0.01, body=(vertices, triangles), policy="bridge", brep=text, stats=mesh_stats)
    assert mesh_stats["rerouted_bridges"] == rerouted and mesh_stats["bridges"] == len(plan["bridges"])
