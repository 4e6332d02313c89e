"""Rings: a CurvedLattice whose groups come round to the first ones after whole turns about its axis.

When U (or V) turns by a full turn or more over the lattice (TurnsU, TurnsV), group q along it may fall exactly on
group 0 (its step to the q-th power is the identity: a whole number of turns and no growth). The groups from q on
then repeat the first ones: they are left out, and the ring is closed by seam beam patterns: a pattern (n1, d, ...,
n2) with d > 0 along that direction also joins the last groups to the first with the offset d - q (the kernel's
lattice joins group i to group i + d - q only where that group exists, that is exactly across the seam; node n2 of
group i + d - q is where node n2 of group i + d would be, since the step to the q-th power is the identity). The
result is an ordinary steady lattice with a few more beam patterns: every consumer takes it as it is.

A sheet that winds over itself without closing exactly (a helix whose turns touch, a turn and a bit) is refused by
far_contacts: elements of groups that are not neighbours in the layout meet."""
import math

# Balls closer than this fraction of their radius are the same ball: the kernel's clean check counts elements this
# close as meeting (kCleanRelativeGap, steady/query/clean_check.hpp), so they could be neither kept apart nor built.
SAME_BALL = 1e-6
DIRECTIONS = "UV"


def turn_sense(angle, other):
    """+1 or -1: the way a direction turns about the axis (its principal angle), or when it does not turn, the way
    the other direction does; +1 when neither turns. Whole turns (TurnsU, TurnsV) are added this way."""
    return -1 if angle < 0.0 or (angle == 0.0 and other < 0.0) else 1


def _group_balls(lattice, i, j, k):
    return [lattice.ball(i, j, k, n) for n in range(lattice.node_count)]


def _same_groups(lattice, first, other):
    for (p, r), (q, s) in zip(_group_balls(lattice, *first), _group_balls(lattice, *other)):
        if math.dist(p, q) > SAME_BALL * min(r, s):
            return False
    return True


def _winds_a_full_turn(becots_map, direction, count):
    """Whether the groups along `direction` span a full turn about the axis (only then can one fall on the first)."""
    log = becots_map.log_u if direction == 0 else becots_map.log_v
    return abs(log.imag) * (count - 1) / count >= 2.0 * math.pi * (1.0 - 1e-9)


def closing_count(lattice, becots_map, direction):
    """The smallest q >= 1 such that the groups q along `direction` (0: U, 1: V) lie on the first ones, every node
    of every group (the ring closes after q groups), or None when no group repeats the first."""
    counts = lattice.counts
    if not _winds_a_full_turn(becots_map, direction, counts[direction]):
        return None
    for q in range(1, counts[direction]):
        step = (q, 0, 0) if direction == 0 else (0, q, 0)
        if not _same_groups(lattice, (0, 0, 0), step):
            continue
        # the layout is steady, so this holds for every group; checked on every group of the first row anyway
        others = range(counts[1 - direction])
        for other in others:
            for k in range(counts[2]):
                first = (0, other, k) if direction == 0 else (other, 0, k)
                moved = (q, other, k) if direction == 0 else (other, q, k)
                if not _same_groups(lattice, first, moved):
                    return None
        return q
    return None


def closed_ring(lattice, direction, q, prop):
    """The lattice with q groups along `direction` and the seam patterns joining the last groups to the first.
    Raises ValueError naming `prop` (the cells property) for a ring of fewer than 3 groups, whose seam beams would
    join the same groups twice, straight through the axis."""
    import steadylattice as sl
    if q < 3:
        raise ValueError("%s: the ring closes after %d groups (group %d falls on group 0); a ring needs at least 3 "
                         "(its seam would join the same groups twice through the axis): use more cells, fewer turns"
                         % (prop, q, q))
    patterns = list(lattice.beam_patterns)
    seams = []
    for pattern in patterns:
        d = pattern[1 + direction]
        if d == 0:
            continue
        if abs(d) >= q:
            raise ValueError("%s: a beam pattern reaches %d groups along the ring of %d groups" % (prop, d, q))
        seam = list(pattern)
        seam[1 + direction] = d - q if d > 0 else d + q
        seams.append(tuple(seam))
    counts = list(lattice.counts)
    counts[direction] = q
    return sl.Lattice(lattice.nodes, patterns + seams, tuple(counts), lattice.U, lattice.V, lattice.W, lattice.G,
                      order=lattice.order)


def _ball_groups(lattice, ball):
    return [tuple(lattice.ball_id(ball)[:2])]


def _beam_groups(lattice, beam):
    """The groups (i, j) of a beam's two ends."""
    i, j, _, p = lattice.beam_id(beam)
    pattern = lattice.beam_patterns[p]
    return [(i, j), (i + pattern[1], j + pattern[2])]


def _neighbours(a, b, ring):
    """Whether groups a and b are within one group of each other, going round the ring (direction, q) if closed."""
    for axis in (0, 1):
        gap = abs(a[axis] - b[axis])
        if ring is not None and ring[0] == axis:
            gap = min(gap, ring[1] - gap)
        if gap > 1:
            return False
    return True


def far_contacts(lattice, ring=None, limit=3):
    """The clean check's contacts (balls or beams meeting) between elements of groups that are not neighbours in
    the layout: the sheet winding over itself. ring: (direction, q) of a closed ring, whose seam makes the last and
    first groups neighbours. Returns up to `limit` messages, and the count."""
    report = lattice.clean_check()
    found = []
    for issue in report["issues"]:
        if issue["kind"] == "circle_overlap":
            continue  # crowded exit circles on one ball: the builders make such hubs
        if issue["kind"] == "ball_ball":
            first, second = _ball_groups(lattice, issue["ball"]), _ball_groups(lattice, issue["other_ball"])
        elif issue["kind"] == "ball_beam":
            first, second = _ball_groups(lattice, issue["ball"]), _beam_groups(lattice, issue["beam"])
        else:
            first, second = _beam_groups(lattice, issue["beam"]), _beam_groups(lattice, issue["other_beam"])
        if not any(_neighbours(a, b, ring) for a in first for b in second):
            found.append(issue["message"])
    return found[:limit], len(found)
