"""Draws docs/images/cots_maps.png from the steadylattice module: a planar COTS tiling, a self-overlapping one with
the two pre-images of a point, and a BeCOTS sheet bent onto a cone above its flat shadow; and
docs/images/becots_lattice.png: BeCOTS lattices meshed by the kernel (a triangle-mesh slab and a two-layer Kagome
stack joined by beams between the layers).
Run: PYTHONPATH=build/python /usr/bin/python3 docs/diagrams/cots_figures.py [output folder]"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Polygon  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

import steadylattice as sl  # noqa: E402
from PIL import Image  # noqa: E402


def save(fig, out):
    """Saves the figure as a palette PNG (a third of the bytes of matplotlib's RGBA, no visible change)."""
    fig.savefig(out)
    Image.open(out).convert("RGB").quantize(colors=128).save(out, optimize=True)
    print(out)

P1 = ((0.0, 0.0), (0.1, 1.0), (1.3, 1.2), (1.0, 0.0))


def tile_outline(m, i, j, n, samples=12):
    """The boundary of tile (i, j) of an n x n grid, sampled along its four log-spiral edges."""
    t = np.linspace(0, 1, samples)
    x0, x1, y0, y1 = i / n, (i + 1) / n, j / n, (j + 1) / n
    uv = np.vstack([np.column_stack([x0 + (x1 - x0) * t, y0 + 0 * t]), np.column_stack([x1 + 0 * t, y0 + (y1 - y0) * t]),
                    np.column_stack([x1 - (x1 - x0) * t, y1 + 0 * t]), np.column_stack([x0 + 0 * t, y1 - (y1 - y0) * t])])
    return m.map(uv)


def draw_planar(ax):
    m = sl.CotsMap(*P1)
    n = 6
    for i in range(n):
        for j in range(n):
            shade = 0.55 + 0.35 * ((i + j) % 2)
            ax.add_patch(Polygon(tile_outline(m, i, j, n), closed=True, facecolor=(shade, shade, 0.95), edgecolor="navy",
                                 linewidth=0.6))
    # a disk per tile, all similar copies of the first one (TS: X_ij = S_ij X_00)
    for i in range(n):
        for j in range(n):
            s = m.tile_similarity(i, j, n, n)
            c = s.apply(m.map((0.5 / n, 0.5 / n)))
            ax.add_patch(plt.Circle(c, 0.025 * s.scale, color="darkorange"))
    for name, p in zip("abcd", P1):
        ax.plot(*p, "ko", ms=3)
        ax.annotate(name, p, textcoords="offset points", xytext=(-10 if name in "ab" else 5, -10 if name in "ad" else 4))
    ax.set_title("COTS map of P1, 6 x 6 similar tiles", fontsize=9)
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.axis("off")


def draw_overlap(ax):
    spiral = sl.CotsMap.from_spiral((1, 0), (0, 0), 0.15 + 7j, 0.5 + 1j)
    m = sl.CotsMap(*spiral.corners, branches=(1, 0))
    n = 8
    for i in range(n):
        for j in range(n):
            ax.add_patch(Polygon(tile_outline(m, i, j, n, 8), closed=True, facecolor=(0.2, 0.4, 0.9, 0.18),
                                 edgecolor=(0.1, 0.2, 0.5, 0.6), linewidth=0.4))
    q = m.map((0.95, 0.3))
    uv = m.inverse(q)
    for (x, y), colour in zip(uv, ("crimson", "darkgreen")):
        i, j = min(int(x * n), n - 1), min(int(y * n), n - 1)
        ax.add_patch(Polygon(tile_outline(m, i, j, n), closed=True, facecolor="none", edgecolor=colour, linewidth=1.5))
    ax.plot(*q, "k*", ms=8)
    ax.plot(0, 0, "k+", ms=8)
    ax.set_title("self-overlapping range: %d pre-images of the star" % len(uv), fontsize=9)
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.axis("off")


def draw_becots(fig, position):
    ax = fig.add_subplot(position, projection="3d")
    flat = sl.BecotsMap.from_field((0, 0, 0), (0, 0, 1), (1, 0, 0), 0.2 + 1.5j, 0.6 + 0.2j)
    bent = flat.bent(0.6)
    n, k = 6, 10
    for m, face, edge in ((flat, (0.8, 0.8, 0.8, 0.35), (0.5, 0.5, 0.5, 0.5)),
                          (bent, (0.95, 0.6, 0.2, 0.55), (0.45, 0.2, 0.0, 0.9))):
        t = np.linspace(0, 1, n * k + 1)
        grid = m.map(np.array([(x, y) for y in t for x in t])).reshape(len(t), len(t), 3)
        ax.plot_surface(grid[..., 0], grid[..., 1], grid[..., 2], color=face, linewidth=0, shade=True)
        for s in range(0, n * k + 1, k):
            ax.plot(*grid[s, :, :].T, color=edge, linewidth=0.5)
            ax.plot(*grid[:, s, :].T, color=edge, linewidth=0.5)
    apex = bent.apex
    ax.plot(*np.array([apex, apex + 2.5 * bent.axis]).T, "k--", linewidth=0.8)
    ax.plot(*apex, "ko", ms=3)
    ax.set_title("BeCOTS: the sheet bent onto a cone (beta = 0.6)", fontsize=9)
    ax.view_init(elev=22, azim=-75)
    ax.set_box_aspect((1, 1, 0.8))
    ax.axis("off")


def draw_mesh(ax, lattice, tolerance, title):
    vertices, triangles = lattice.to_mesh(tolerance)
    tri = vertices[triangles]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-300)
    light = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    shade = 0.35 + 0.65 * np.clip(normals @ light, 0, 1)
    colours = np.column_stack([0.95 * shade, 0.6 * shade, 0.25 * shade, np.ones_like(shade)])
    ax.add_collection3d(Poly3DCollection(tri, facecolors=colours, linewidths=0))
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    centre, half = (lo + hi) / 2, (hi - lo).max() / 2
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_zlim(centre[2] - half, centre[2] + half)
    ax.set_title("%s: %d balls, %d beams, %d triangles" % (title, lattice.ball_count, lattice.beam_count,
                                                          len(triangles)), fontsize=9)
    ax.view_init(elev=35, azim=-70)
    ax.set_box_aspect((1, 1, 1), zoom=1.5)
    ax.axis("off")


def draw_lattices(out):
    sheet = sl.BecotsMap.from_field((0, 0, 0), (0, 0, 1), (1, 0, 0), 0.2 + 1.5j, 0.6 + 0.2j)
    cone = sheet.bent(0.6)
    fig = plt.figure(figsize=(12, 5.5), dpi=110)
    slab = sl.becots_lattice(cone, "triangle", (14, 9, 1), 0.02, beam_ratio=0.5)
    draw_mesh(fig.add_subplot(1, 2, 1, projection="3d"), slab, 0.002, "triangle-mesh BeCOTS slab")
    nodes, beams = sl.becots_connectivity("kagome")
    beams = beams + [(n, 0, 0, 1, n) for n in range(len(nodes))]  # beams between the layers
    stack = sl.becots_lattice(cone, (nodes, beams), (8, 6, 2), 0.011, layer_raise=0.15, beam_ratio=0.5)
    draw_mesh(fig.add_subplot(1, 2, 2, projection="3d"), stack, 0.0012, "Kagome BeCOTS stack, 2 layers")
    fig.tight_layout()
    save(fig, out)


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "images")
    out = os.path.join(folder, "cots_maps.png")
    fig = plt.figure(figsize=(12, 4), dpi=110)
    draw_planar(fig.add_subplot(1, 3, 1))
    draw_overlap(fig.add_subplot(1, 3, 2))
    draw_becots(fig, 133)
    fig.tight_layout()
    save(fig, out)
    draw_lattices(os.path.join(folder, "becots_lattice.png"))


if __name__ == "__main__":
    main()
