"""The kernel from plain Python (no FreeCAD needed: /usr/bin/python3 examples/kernel_queries.py): a bent, twisted,
tapered lattice of a million beams, queried without listing it: which elements a ball touches, point membership,
distances, ray hits, a voxel grid, and its exact volume. Writes the voxel grid as a numpy file.

Output: $LATTICE_OUT or ./out/kernel_queries.npy
"""
import math
import os
import time

import numpy as np

import steadylattice as sl


def main():
    out_dir = os.environ.get("LATTICE_OUT", os.path.join(os.getcwd(), "out"))
    os.makedirs(out_dir, exist_ok=True)
    U = sl.Similarity.swirl(0.004, (0, 0, 1), (0, -250, 0), 1.001)  # bend and taper along i
    V = sl.Similarity.translation((0, 1, 0))
    W = sl.Similarity.screw(0.003, (0, 0, 1), (0, 50, 0), 1.0)  # twist along k
    lattice = sl.Lattice([((0, 0, 0), 0.3)], [(0, 1, 0, 0, 0, 0.12, 0.12), (0, 0, 1, 0, 0, 0.12, 0.12),
                                              (0, 0, 0, 1, 0, 0.12, 0.12)], (100, 100, 100), U, V, W)
    start = time.time()
    centre, _ = lattice.ball(50, 50, 50, 0)  # O(1): no listing of the lattice
    balls, beams = lattice.query_ball(centre + (0.2, 0.1, 0.3), 0.8)
    points = np.random.default_rng(1).uniform(centre - 10, centre + 10, size=(20000, 3))
    inside = lattice.contains(points)
    distances = lattice.distance(points[:1000], 2.0)
    hits = lattice.raycast(np.array([centre + (0.5, 0.5, 0.0)]), np.array([[1.0, 0.0, 0.0]]))
    voxels = lattice.voxelize(centre - 5, centre + 5, (40, 40, 40))
    volume = lattice.properties()["volume"]
    print("%d beams; a ball of radius 0.8 touches %d balls and %d beams; %.2f %% of 20,000 points near it inside; "
          "a ray hits after %.3f mm; %d of %d voxels full; exact volume %.3f mm^3; all in %.2f s"
          % (lattice.beam_count, len(balls), len(beams), 100.0 * inside.mean(), float(hits[0]), int(voxels.sum()),
             voxels.size, volume, time.time() - start))
    assert math.isfinite(volume) and volume > 0 and len(distances) == 1000
    path = os.path.join(out_dir, "kernel_queries.npy")
    np.save(path, voxels)
    return path


if __name__ in ("__main__", "kernel_queries"):
    main()
