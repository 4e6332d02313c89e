"""How far a mesh of the main job's part lies from the exact part: the lattice trimmed to the inner offset of a
cylinder, united with the skin between the cylinder and that offset (the B-rep part's definition). Signed
distances are combined the usual way (intersection: max, union: min): exact outside the lattice and for the
cylinders, and inside the lattice the depth in the deepest single ball or beam (the kernel's exact distance
query takes about 160 us a point, too slow for a million points), so at a crease the deviation is measured low
rather than high. Sample points: the centroid and the edge midpoints of every triangle (of every
stride-th one when there are many)."""
import numpy as np

SAMPLED_TRIANGLES = 150000
MARGIN = 0.5  # distances to the lattice beyond this are not needed (the deviations measured are far smaller)


def cylinder_distance(q, radius, z0, z1):
    """Signed distance from local points q (N x 3) to the solid cylinder about z of `radius` between z0 and z1."""
    r = np.hypot(q[:, 0], q[:, 1]) - radius
    z = np.maximum(z0 - q[:, 2], q[:, 2] - z1)
    return np.hypot(np.maximum(r, 0.0), np.maximum(z, 0.0)) + np.minimum(np.maximum(r, z), 0.0)


def beam_distance(q, ca, cb, ra, rb):
    """Signed distance from points q to the convex hull of the balls (ca, ra) and (cb, rb)."""
    axis = cb - ca
    length = np.linalg.norm(axis)
    u = axis / length
    w = q - ca
    x = w @ u
    y = np.linalg.norm(w - np.outer(x, u), axis=1)
    s = (ra - rb) / length  # sine of the half-angle
    c = np.sqrt(max(0.0, 1.0 - s * s))
    k = x * c - y * s  # where the nearest point of the tangent line lies, from a's tangent point
    lateral = x * s + y * c - ra
    at_a = np.linalg.norm(w, axis=1) - ra
    at_b = np.linalg.norm(q - cb, axis=1) - rb
    return np.where(k < 0.0, at_a, np.where(k > length * c, at_b, lateral))


class PointGrid:
    """Points bucketed in cubic cells, for the points inside a box."""

    def __init__(self, points, cell):
        self.points, self.cell = points, cell
        self.lo = points.min(axis=0) if len(points) else np.zeros(3)
        ijk = np.floor((points - self.lo) / cell).astype(np.int64)
        self.dims = ijk.max(axis=0) + 1 if len(points) else np.ones(3, dtype=np.int64)
        keys = (ijk[:, 0] * self.dims[1] + ijk[:, 1]) * self.dims[2] + ijk[:, 2]
        self.order = np.argsort(keys, kind="stable")
        self.keys = keys[self.order]

    def inside(self, lo, hi):
        a = np.maximum(np.floor((lo - self.lo) / self.cell).astype(np.int64), 0)
        b = np.minimum(np.floor((hi - self.lo) / self.cell).astype(np.int64), self.dims - 1)
        if np.any(a > b):
            return np.zeros(0, dtype=np.int64)
        i, j, k = np.meshgrid(np.arange(a[0], b[0] + 1), np.arange(a[1], b[1] + 1), np.arange(a[2], b[2] + 1),
                              indexing="ij")
        cells = ((i * self.dims[1] + j) * self.dims[2] + k).ravel()
        first, last = np.searchsorted(self.keys, cells), np.searchsorted(self.keys, cells, side="right")
        idx = np.concatenate([self.order[f:l] for f, l in zip(first, last) if l > f] or [np.zeros(0, np.int64)])
        p = self.points[idx]
        return idx[np.all((p >= lo) & (p <= hi), axis=1)]


class ExactPart:
    def __init__(self, part):
        from latticewb.kernel import lattice_part
        body = part.Body
        if body is None or body.TypeId != "Part::Cylinder":
            raise ValueError("Body: the deviation is measured for a part cut from a Part::Cylinder (the main job)")
        self.lattice, _, _, self.skin, _ = lattice_part.kernel_request(part)
        self.radius, self.height = float(body.Radius), float(body.Height)
        m = body.Placement.inverse().toMatrix()
        self.rotation = np.array([[m.A11, m.A12, m.A13], [m.A21, m.A22, m.A23], [m.A31, m.A32, m.A33]])
        self.shift = np.array([m.A14, m.A24, m.A34])
        self.centers, self.radii = self.lattice.balls()
        self.beams = self.lattice.beams()

    def lattice_distance(self, p):
        """Signed distance to the lattice, up to MARGIN (farther points get MARGIN): the nearest ball or beam."""
        d = np.full(len(p), MARGIN)
        grid = PointGrid(p, 2.0 * float(self.radii.max()) + MARGIN)
        for c, r in zip(self.centers, self.radii):
            idx = grid.inside(c - r - MARGIN, c + r + MARGIN)
            if len(idx):
                d[idx] = np.minimum(d[idx], np.linalg.norm(p[idx] - c, axis=1) - r)
        a, b, ra, rb = self.beams
        for i in range(len(a)):
            ca, cb = self.centers[a[i]], self.centers[b[i]]
            if np.linalg.norm(cb - ca) <= abs(ra[i] - rb[i]):
                continue  # one end ball holds the other: the balls cover it
            idx = grid.inside(np.minimum(ca - ra[i], cb - rb[i]) - MARGIN, np.maximum(ca + ra[i], cb + rb[i]) + MARGIN)
            if len(idx):
                d[idx] = np.minimum(d[idx], beam_distance(p[idx], ca, cb, ra[i], rb[i]))
        return d

    def distance(self, p):
        """Signed distance from points p (N x 3) to the exact part: (lattice ∩ inner) ∪ (body minus inner)."""
        q = p @ self.rotation.T + self.shift
        body = cylinder_distance(q, self.radius, 0.0, self.height)
        inner = cylinder_distance(q, self.radius - self.skin, self.skin, self.height - self.skin)
        return np.minimum(np.maximum(self.lattice_distance(p), inner), np.maximum(body, -inner))

    def deviation(self, vertices, triangles):
        """The largest distance from the exact part's surface over the sample points of a mesh."""
        t = np.asarray(triangles)[::max(1, len(triangles) // SAMPLED_TRIANGLES)]
        v = np.asarray(vertices, dtype=float)
        a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
        points = np.concatenate([(a + b + c) / 3.0, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)])
        return float(np.abs(self.distance(points)).max())
