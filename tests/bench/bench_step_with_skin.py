"""Issue 14's large STEP: a swirled lattice (bench_brep's scale lattice: one node of radius 0.25, three beams of
unequal end radii, U a slight swirl) trimmed into a cylinder 3 degrees off its beams with a skin of 0.4, written
as a STEP assembly and read back by OpenCASCADE's reader (in a reader process). Prints the beams, the write time,
the file's size per beam, the peak memory, the read time, and each part's validity, solids and volume.
Default: 12 x 12 x 8 nodes, 3,120 beams (33 s to write on the shared machine, 2.4 KB per beam, 18 s to read; 87
loose edges retraced; 3.5 KB per beam before the reals went to nine decimals and the intersection edges were
refitted); --long: 101,343 beams (issue 14's 100,000-beam target: written in 2,739 s on a machine running two
other jobs, 207.0 MB, 2.0 KB per beam, 1,145 of 1,158 loose edges retraced and the intersection edges refitted in
22.2 s, read back with the parts' checks in 530 s, both valid; peak 9.8 GB. Before the reals went to nine
decimals and the edges were refitted: 269.1 MB, 2,257 s and 692 s, peak 10.6 GB. Before the retrace: 237.5 MB,
1,674 s and 773 s; before equal geometry was shared: 1,137.5 MB, read back in 2,553 s).
Usage: bench_step_with_skin.py [--long]"""
import os
import resource
import sys
import tempfile
import time

import steadylattice as sl

sys.path.append("/usr/lib/freecad/lib")
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import FreeCAD  # noqa: E402
import Part  # noqa: E402
from step_read_back import read_back_and_print  # noqa: E402  (tests/common)


def lattice(counts):
    S = sl.Similarity
    nodes = [((0, 0, 0), 0.25)]
    beams = [(0, 1, 0, 0, 0, 0.10, 0.12), (0, 0, 1, 0, 0, 0.11, 0.09), (0, 0, 0, 1, 0, 0.08, 0.10)]
    return sl.Lattice(nodes, beams, counts, S.swirl(0.004, (0, 0, 1), (0, -250, 0), 1.0005), S.translation((0, 1, 0)),
                      S.translation((0, 0, 1)))


def cylinder_body(lat, tilt=0.05):
    """BREP text of a cylinder across the lattice, its axis `tilt` off the beams (as bench_brep's)."""
    centers, _ = lat.balls()
    lo, hi = centers.min(0), centers.max(0)
    mid = 0.5 * (lo + hi)
    radius, height = 0.5 * min(hi[0] - lo[0], hi[1] - lo[1]), 0.9 * (hi[2] - lo[2])
    return Part.makeCylinder(radius, height, FreeCAD.Vector(mid[0], mid[1], mid[2] - height / 2),
                             FreeCAD.Vector(tilt, 0.6 * tilt, 1)).exportBrepToString()


def main():
    counts = (33, 33, 32) if "--long" in sys.argv else (12, 12, 8)
    lat = lattice(counts)
    body = cylinder_body(lat)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "lattice_part.step")
        start = time.perf_counter()
        stats = {}
        lat.write_step(path, body=body, skin=0.4, stats=stats)
        write = time.perf_counter() - start
        size = os.path.getsize(path)
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        print("beams %d, written in %.1f s, %.1f MB (%.1f KB per beam), peak %.0f MB, %d crossing hubs" % (
            lat.beam_count, write, size / 1e6, size / 1e3 / lat.beam_count, peak, stats["crossing_hubs"]), flush=True)
        print("loose edges of the Booleans %d (up to %.1e), retraced %d (now up to %.1e) in %.1f s" % (
            stats["loose_edges"], stats["loosest_edge_before"], stats["retraced_edges"], stats["loosest_edge_after"],
            stats["retrace_seconds"]), flush=True)
        _, all_valid = read_back_and_print(path)
        if not all_valid:
            sys.exit(1)


if __name__ == "__main__":
    main()
