"""A STEP the kernel wrote, read back by OpenCASCADE's reader (steadylattice.read_step, in a reader process), timed
and printed part by part, as the STEP benchmarks report it."""
import time

import steadylattice as sl


def read_back_and_print(path, volume_digits=6):
    """The parts read back from `path`, after printing the read's time and each part's validity, solids, faces and
    volume; and whether every part is one valid solid."""
    start = time.perf_counter()
    parts = sl.read_step(path)
    print("read back by OpenCASCADE in %.1f s" % (time.perf_counter() - start))
    for p in parts:
        print("  %-8s valid %s, %d solids, %d faces, volume %.*f" % (
            p["name"], p["valid"], p["solids"], p["faces"], volume_digits, p["volume"]))
    return parts, all(p["valid"] and p["solids"] == 1 for p in parts)
