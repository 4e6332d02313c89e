"""Draws docs/images/steady_slab.png from the steadylattice module: a planar steady 2-map through five points (its
warped tile grid, the five points), and the rectified steady slab on it (every ball a copy of the rectified
template, placed by V^(j/nv) o U^(i/nu); beams drawn as their hull's outline in the plane).
Run: PYTHONPATH=build/python /usr/bin/python3 docs/diagrams/steady_map2_figure.py [output folder]"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Circle, Polygon  # noqa: E402
from PIL import Image  # noqa: E402

import steadylattice as sl  # noqa: E402

POINTS = ((0.0, 0.0), (10.0, 1.0), (-1.0, 9.0), (8.0, 11.0), (5.2, 1.4))
NU, NV = 7, 6


def grid_lines(ax, m):
    t = np.linspace(0, 1, 80)
    for i in range(NU + 1):
        p = m.map(np.column_stack([np.full_like(t, i / NU), t]))
        ax.plot(p[:, 0], p[:, 1], color="0.75", lw=0.8)
    for j in range(NV + 1):
        p = m.map(np.column_stack([t, np.full_like(t, j / NV)]))
        ax.plot(p[:, 0], p[:, 1], color="0.75", lw=0.8)


def hull_outline(c0, r0, c1, r1):
    """The outline in the plane of the hull of two disks (the beam's section through its axis)."""
    d = c1 - c0
    length = np.linalg.norm(d)
    e = d / length
    n = np.array([-e[1], e[0]])
    s = (r0 - r1) / length
    c = np.sqrt(max(0.0, 1 - s * s))
    a0, a1 = c0 + r0 * (s * e + c * n), c1 + r1 * (s * e + c * n)
    b0, b1 = c0 + r0 * (s * e - c * n), c1 + r1 * (s * e - c * n)
    return np.array([a0, a1, b1, b0])


def main(folder):
    m = sl.SteadyMap2.from_points(*POINTS)
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.2))
    ax = axes[0]
    grid_lines(ax, m)
    names = "abcde"
    for k, p in enumerate(POINTS):
        ax.plot(*p, "o", color="tab:red", ms=5)
        ax.annotate(names[k], p, textcoords="offset points", xytext=(5, 4), color="tab:red")
    ax.set_title("steady 2-map M(u, v) = V^v U^u (a) through five points")
    ax = axes[1]
    grid_lines(ax, m)
    lat = m.slab([((0.5, 0.5, 0.0), 0.035)], [(0, 1, 0, 0, 0), (0, 0, 1, 0, 0), (0, 1, 1, 0, 0)], (NU, NV, 1),
                 beam_ratio=0.45)
    centers, radii = lat.balls()
    start, end, beam_a, beam_b = lat.beams()
    for k in range(len(start)):
        a, b = start[k], end[k]
        ra, rb = beam_a[k], beam_b[k]
        ax.add_patch(Polygon(hull_outline(centers[a][:2], ra, centers[b][:2], rb), color="tab:blue", alpha=0.55, lw=0))
    for c, r in zip(centers, radii):
        ax.add_patch(Circle(c[:2], r, color="tab:blue"))
    ax.set_title("rectified steady slab (7 x 6 groups): copies of one template")
    for ax in axes:
        ax.set_aspect("equal")
        ax.axis("off")
    fig.tight_layout()
    out = os.path.join(folder, "steady_slab.png")
    fig.savefig(out, dpi=90)
    Image.open(out).convert("RGB").quantize(colors=128).save(out, optimize=True)
    print(out)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "images"))
