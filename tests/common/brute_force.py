"""Brute-force lattice geometry in numpy, the slow and obviously right twins of the kernel's fast paths, shared by
the Python module's tests (tests/python) and the FreeCAD tests (tests/freecad).

A beam is the convex hull of two balls, which is the union of the balls interpolated between them; so the signed
gap from a point to a beam is min over t in [0, 1] of |p - c(t)| - r(t), a convex function of t minimized here by
ternary search. Independent of the kernel's closed forms."""
import numpy as np


def hull_gap(points, ca, ra, cb, rb, iterations=80):
    """Signed gap from points to hulls of balls (ca, ra), (cb, rb), negative inside. Points (N, 3) against one
    beam, or one point (3,) against beams (M, 3) / (M,): numpy broadcasting pairs them."""
    points, ca, cb = np.asarray(points, float), np.asarray(ca, float), np.asarray(cb, float)
    ra, rb = np.asarray(ra, float), np.asarray(rb, float)
    shape = np.broadcast_shapes(points.shape[:-1], ca.shape[:-1], ra.shape)
    t0, t1 = np.zeros(shape), np.ones(shape)

    def gap(t):
        c = ca + t[..., None] * (cb - ca)
        return np.linalg.norm(points - c, axis=-1) - (ra + t * (rb - ra))

    for _ in range(iterations):
        m1, m2 = t0 + (t1 - t0) / 3, t1 - (t1 - t0) / 3
        left = gap(m1) < gap(m2)
        t1 = np.where(left, m2, t1)
        t0 = np.where(left, t0, m1)
    # the ends too: the minimum may sit at t = 0 or 1, where ternary search only converges
    return np.minimum(np.minimum(gap(np.zeros(shape)), gap(np.ones(shape))), gap((t0 + t1) / 2))


def gap_to_beam(points, ca, ra, cb, rb, iterations=60):
    """Signed gap from each of points (N, 3) to one beam."""
    return hull_gap(points, ca, ra, cb, rb, iterations)


class Elements:
    """Every ball and beam of a lattice, for queries by brute force."""

    def __init__(self, lattice):
        self.c, self.r = lattice.balls()
        a, b, self.ra, self.rb = lattice.beams()
        self.a, self.b = self.c[a], self.c[b]

    def ball_distances(self, p):
        return np.linalg.norm(self.c - p, axis=1) - self.r

    def beam_distances(self, p):
        return hull_gap(p, self.a, self.ra, self.b, self.rb)

    def query(self, center, radius, tol=1e-9):
        """Indices certainly inside, and those within tol of the boundary (either answer is right)."""
        db, de = self.ball_distances(center) - radius, self.beam_distances(center) - radius
        return (np.flatnonzero(db <= -tol), np.flatnonzero(np.abs(db) < tol),
                np.flatnonzero(de <= -tol), np.flatnonzero(np.abs(de) < tol))

    def distance(self, p):
        d = min(self.ball_distances(p).min(initial=np.inf), self.beam_distances(p).min(initial=np.inf))
        return max(0.0, d)


def gap_to_lattice(points, lattice, ball_mask=None, beam_mask=None):
    """Signed gap from each point to the lattice (negative inside): min over balls and beams."""
    centers, radii = lattice.balls()
    a, b, ra, rb = lattice.beams()
    best = np.full(len(points), np.inf)
    for q, (c, r) in enumerate(zip(centers, radii)):
        if ball_mask is None or ball_mask[q]:
            best = np.minimum(best, np.linalg.norm(points - c, axis=1) - r)
    for q, (i, j, r1, r2) in enumerate(zip(a, b, ra, rb)):
        if beam_mask is None or beam_mask[q]:
            best = np.minimum(best, gap_to_beam(points, centers[i], r1, centers[j], r2))
    return best


def inside_lattice(points, lattice):
    """Membership, with a bounding-box prefilter per beam so that many points stay affordable."""
    centers, radii = lattice.balls()
    a, b, ra, rb = lattice.beams()
    inside = np.zeros(len(points), dtype=bool)
    for c, r in zip(centers, radii):
        inside |= np.einsum("ij,ij->i", points - c, points - c) <= r * r
    for i, j, r1, r2 in zip(a, b, ra, rb):
        ca, cb = centers[i], centers[j]
        lo, hi = np.minimum(ca, cb) - max(r1, r2), np.maximum(ca, cb) + max(r1, r2)
        near = np.where(np.all((points >= lo) & (points <= hi), axis=1) & ~inside)[0]
        if len(near):
            inside[near[gap_to_beam(points[near], ca, r1, cb, r2, 40) <= 0.0]] = True
    return inside


def beams_between(lattice, ball_mask):
    """The beam mask of a node mask: a beam is kept when both its nodes are."""
    a, b, _, _ = lattice.beams()
    return ball_mask[a] & ball_mask[b]
