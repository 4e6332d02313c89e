"""Issue 16, item 2: a lattice of 10^9 elements defined, queried and measured within 2 GiB of address space.

Run under the limit (docs/reliability.md):
    prlimit --as=2147483648 env PYTHONPATH=build/python /usr/bin/python3 tests/bench/billion_elements.py
Prints one line per step with its time and the process's peak resident memory; exits 1 if a step fails."""
import resource
import sys
import time

import numpy as np

import steadylattice as sl


def peak_mib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def step(name, call):
    t = time.time()
    result = call()
    print("%-60s %8.3f s  peak %6.0f MiB  %s" % (name, time.time() - t, peak_mib(), result), flush=True)
    return result


def main():
    print("RLIMIT_AS:", resource.getrlimit(resource.RLIMIT_AS)[0])
    t = sl.Similarity.translation
    n = 1000
    # A twisted, tapered cubic lattice (steady, not a plain grid): 10^9 balls and 2,997,000,000 beams.
    U = sl.Similarity.swirl(0.0005, (0, 0, 1), (0, -2000, 0), 1.0)
    W = sl.Similarity.screw(0.0002, (0, 0, 1), (0, 0, 0), 1.0)
    beams = [(0, 1, 0, 0, 0, 0.1, 0.1), (0, 0, 1, 0, 0, 0.1, 0.1), (0, 0, 0, 1, 0, 0.1, 0.1)]
    lat = step("define 1000^3 groups", lambda: sl.Lattice([((0, 0, 0), 0.2)], beams, (n, n, n), U, t((0, 1, 0)), W))
    step("ball_count, beam_count", lambda: (lat.ball_count, lat.beam_count))
    assert lat.ball_count == 10**9
    step("ball(123, 456, 789, 0), ball_id, beam_index", lambda: (
        lat.ball(123, 456, 789, 0)[1], lat.ball_id(123456789), lat.beam_index(999, 999, 998, 2)))
    center = np.array(lat.ball(500, 500, 500, 0)[0])
    step("query_ball at ball (500, 500, 500), radius 3", lambda: len(lat.query_ball(tuple(center), 3.0)[0]))
    rng = np.random.default_rng(1)
    points = center + rng.uniform(-50, 50, size=(10000, 3))
    step("contains, 10^4 points", lambda: int(np.count_nonzero(lat.contains(points))))
    step("distance (bound 5), 10^4 points", lambda: float(np.nanmin(lat.distance(points, bound=5.0))))
    step("raycast, 10^4 rays", lambda: int(np.isfinite(lat.raycast(points, np.tile((1.0, 0.3, 0.2), (10000, 1)))).sum()))
    props = step("properties() (closed-form sums, clean check)", lambda: round(lat.properties()["volume"], 3))
    # Refusals, not crashes, for what cannot fit: a listing of all the balls
    try:
        lat.balls()
        print("balls(): listed?!")
        return 1
    except MemoryError as e:
        print("balls(): refused at once:", str(e)[:160])
    print("peak resident memory %.0f MiB" % peak_mib())
    return 0


if __name__ == "__main__":
    sys.exit(main())
