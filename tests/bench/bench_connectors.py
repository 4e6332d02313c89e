"""Connectors of constant-radius lattices: families, their members, build time per family, the cut list and the
STEP assembly, on BeCOTS slabs (triangle, kagome, honeycomb) and a cubic grid. Rods are a tenth of the shortest
beam; the reach is the middle of the range that fits (Lattice.connector_reach_range).

Run: PYTHONPATH=build/python /usr/bin/python3 tests/bench/bench_connectors.py   (about a minute on 2 cores)
"""
import os
import tempfile
import time

import numpy as np

import steadylattice as sl


def shortest_beam(lat):
    centers, _ = lat.balls()
    a, b, _, _ = lat.beams()
    return float(np.min(np.linalg.norm(centers[b] - centers[a], axis=1)))


def grid(n):
    t = sl.Similarity.translation
    beams = [(0, 1, 0, 0, 0), (0, 0, 1, 0, 0), (0, 0, 0, 1, 0)]
    return sl.Lattice([((0, 0, 0), 0.2)], beams, (n, n, n), t((1, 0, 0)), t((0, 1, 0)), t((0, 0, 1)))


def main():
    cone = sl.BecotsMap((0, 0, 0), (0.1, 1, 0.2), (1.3, 1.2, -0.3), (1, 0, 0.1))
    cases = [("BeCOTS triangle 12 x 8", sl.becots_lattice(cone, sl.becots_connectivity("triangle"), (12, 8, 1), 0.01)),
             ("BeCOTS kagome 8 x 6", sl.becots_lattice(cone, sl.becots_connectivity("kagome"), (8, 6, 1), 0.01)),
             ("BeCOTS honeycomb 8 x 6", sl.becots_lattice(cone, sl.becots_connectivity("honeycomb"), (8, 6, 1), 0.01)),
             ("cubic grid 6 x 6 x 6", grid(6))]
    print("| lattice | balls / beams | reach range (rod radii) | families (members) | build per family (s) | total (s) | cut-list lengths | STEP assembly (s, MB) |")
    print("|---|---|---|---|---|---|---|---|")
    for name, lat in cases:
        rho = shortest_beam(lat) / 10
        low, high = lat.connector_reach_range(rho)
        start = time.perf_counter()
        c = lat.connectors(rho, reach=0.5 * (low + high))
        total = time.perf_counter() - start
        families = c.families
        members = sorted((f["count"] for f in families), reverse=True)
        seconds = [f["build_seconds"] for f in families]
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "c.step")
            start = time.perf_counter()
            c.write_step(path)
            write = time.perf_counter() - start
            size = os.path.getsize(path) / 1e6
        print("| %s | %d / %d | %.2f to %.2f | %d (%s) | %.2f to %.2f | %.1f | %d | %.1f, %.1f |" % (
            name, lat.ball_count, lat.beam_count, low, high, len(families), ", ".join(map(str, members)),
            min(seconds), max(seconds), total, len(c.cut_list), write, size))
    print("bench: done")


if __name__ == "__main__":
    main()
