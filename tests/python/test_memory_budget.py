"""Issue 16, repro 10: memory refusals are MemoryErrors stated before any work, with the estimate, the budget
(the machine's available memory or the process's RLIMIT_AS, whichever is smaller) and what to do instead.

Limits are set in child processes (resource.setrlimit before exec), so the test process keeps its own."""
import re
import resource
import subprocess
import sys

import pytest

import steadylattice as sl

GIB = 1 << 30

# The child's prelude: the cubic template at any counts, and a report of the exception a call raises.
PRELUDE = """
import steadylattice as sl
t = sl.Similarity.translation
T = (t((1, 0, 0)), t((0, 1, 0)), t((0, 0, 1)))
def cubic(n, beam_radii=True):
    beams = [(0, 1, 0, 0, 0, 0.1, 0.1), (0, 0, 1, 0, 0, 0.1, 0.1), (0, 0, 0, 1, 0, 0.1, 0.1)]
    if not beam_radii:
        beams = [b[:5] for b in beams]
    return sl.Lattice([((0, 0, 0), 0.2)], beams, n, *T)
def report(call):
    try:
        call()
        print("no error")
    except BaseException as e:
        print(type(e).__name__ + ": " + str(e))
"""


def run_limited(code, limit_bytes=None):
    """The last line the child prints, run under RLIMIT_AS = limit_bytes (None: no limit)."""
    def limit():
        if limit_bytes is not None:
            resource.setrlimit(resource.RLIMIT_AS, (limit_bytes, limit_bytes))
    r = subprocess.run([sys.executable, "-c", PRELUDE + code], preexec_fn=limit, capture_output=True, text=True,
                       timeout=900)
    assert "Caught an unknown exception" not in r.stdout + r.stderr
    lines = r.stdout.strip().splitlines()
    assert lines, r.stderr
    return lines[-1]


def figures(message):
    """(estimate, budget, available) in GB from a refusal's text."""
    m = re.search(r"needs ([\d.e+]+) GB, more than the ([\d.e+]+) GB it may use \(75 % of the ([\d.e+]+) GB", message)
    assert m, message
    return tuple(float(x) for x in m.groups())


def test_properties_of_a_lattice_without_nodes_name_omitted():
    t = sl.Similarity.translation
    lat = sl.Lattice([((0, 0, 0), 0.2)], [], (1, 1, 1), t((1, 0, 0)), t((0, 1, 0)), t((0, 0, 1)), omitted=[(0, 0, 0, 0)])
    for call in (lat.properties, lat.properties_brute_force):
        with pytest.raises(ValueError, match=r"^omitted: lists every node of the lattice: it has no ball"):
            call()


def test_brep_refusal_states_consistent_figures_and_what_to_do_instead():
    message = run_limited("report(cubic((70, 70, 70)).brep)")
    assert message.startswith("MemoryError: the B-rep of 2371600 faces needs")
    estimate, budget, available = figures(message)
    assert estimate > budget
    assert budget == pytest.approx(0.75 * available, rel=0.02)
    assert "3MF beam lattice" in message and "mesh" in message and "preview" in message


def test_brep_refusal_respects_the_process_address_space_limit():
    # 55^3 fits this machine's memory but not 5 GB of address space: refused before any work, naming RLIMIT_AS.
    message = run_limited("report(cubic((55, 55, 55)).brep)", 5 * GIB)
    assert message.startswith("MemoryError: the B-rep of ")
    estimate, budget, available = figures(message)
    assert available < 5 * GIB / 1e9 and estimate > budget
    assert "left under this process's address-space limit, RLIMIT_AS" in message


def test_query_ball_holding_a_billion_elements_is_refused_up_front_naming_the_radius():
    message = run_limited("report(lambda: cubic((1000, 1000, 1000)).query_ball((500, 500, 500), 2000.0))", 4 * GIB)
    assert message.startswith("MemoryError: query_ball(radius=2000, center=(500, 500, 500)): a result of at least "
                              "3997000000 balls and beams needs 64 GB")
    assert "RLIMIT_AS" in message and "query smaller balls" in message


def test_query_ball_over_part_of_a_huge_lattice_is_refused_from_its_sure_blocks():
    # The ball does not hold the lattice: the lower bound comes from the index blocks surely inside it.
    message = run_limited("report(lambda: cubic((1000, 1000, 1000)).query_ball((500, 500, 500), 400.0))", 4 * GIB)
    assert message.startswith("MemoryError: query_ball(radius=400, center=(500, 500, 500)): a result of at least ")
    assert "RLIMIT_AS" in message


def test_a_growing_query_result_is_refused_naming_the_radius():
    # A filtered lattice has no up-front estimate (its filter decides); the collected result is checked as it grows.
    code = "report(lambda: sl.FilteredLattice(cubic((400, 400, 400))).query_ball((200, 200, 200), 1000.0))"
    message = run_limited(code, 2 * GIB)
    assert message.startswith("MemoryError: query_ball(radius=1000, center=(200, 200, 200)): a result of more than ")
    assert "RLIMIT_AS" in message


def test_materialize_of_ten_billion_balls_is_refused_up_front():
    code = "report(cubic((10000, 1000, 1000), False).filtered(sl.Gyroid(10.0, 0.5)).materialize)"
    message = run_limited(code, 4 * GIB)
    assert message.startswith("MemoryError: materialize(): a mask of the 10000000000 balls (one byte each) needs 10 GB")
    assert "RLIMIT_AS" in message and "without materializing" in message


def test_without_a_limit_the_budget_is_the_machines():
    message = run_limited("report(lambda: cubic((1000, 1000, 1000)).query_ball((500, 500, 500), 2000.0))")
    assert "this machine has available" in message


def test_a_mesh_with_a_tiny_tolerance_is_refused_before_work_under_rlimit_as():
    """Issue 16, item 2: to_mesh, write_obj and write_3mf hold the whole mesh; at 1e-6 on balls of 0.2 the mesh of
    30^3 cells is far beyond 2 GiB. Refused at once, from the estimate, naming RLIMIT_AS and a tolerance that fits;
    a streamed STL holds only the templates and is refused only when those cannot fit."""
    code = """
import time
L = cubic((30, 30, 30))
t0 = time.time()
report(lambda: L.to_mesh(1e-6))
print("seconds", time.time() - t0)
"""
    lines = subprocess.run([sys.executable, "-c", PRELUDE + code], capture_output=True, text=True, timeout=900,
                           preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_AS, (2 * GIB, 2 * GIB))).stdout
    message, seconds = lines.strip().splitlines()[-2:]
    assert message.startswith("MemoryError: mesh: about "), message
    assert "triangles (estimated from the tolerance 1e-06 and the balls' radii, before any is made)" in message
    assert "RLIMIT_AS" in message and "a tolerance of " in message and "or more fits" in message, message
    assert "write STL (streamed" in message and "write_3mf(beam_lattice=True)" in message, message
    assert float(seconds.split()[1]) < 5.0
    estimate, budget, _ = figures(message)
    assert estimate > budget
    tolerance = float(re.search(r"a tolerance of ([\d.e+-]+) or more fits", message).group(1))
    assert 1e-6 < tolerance < 0.05  # below a quarter of the radius, the largest tolerance the balls allow


def test_the_slab_window_clean_check_fits_a_tight_limit_in_chunks():
    """Issue 16, item 2 (10^9 elements within 2 GiB): the hub-overlap check of a large steady lattice held two whole
    slabs of hubs (1.3 GB each for slabs of 10^6) and refused under a tight RLIMIT_AS; it now makes each slab's hubs
    a chunk at a time when two slabs do not fit, and must find the same overlaps as without a limit."""
    code = """
import re, resource
t = sl.Similarity.translation
beams = [(0, 1, 0, 0, 0, 0.1, 0.1), (0, 0, 1, 0, 0, 0.1, 0.1), (0, 0, 0, 1, 0, 0.1, 0.1)]
# balls of 0.55 at spacing 1 overlap their neighbours: every slab has overlaps to find
L = sl.Lattice([((0, 0, 0), 0.55)], beams, (330, 330, 4), t((1, 0, 0)), t((0, 1, 0)), t((0, 0, 1)))
free = L.hub_overlap_report(max_reports=1)
vm = int(re.search(r"VmSize:\\s+(\\d+)", open("/proc/self/status").read()).group(1)) * 1024
resource.setrlimit(resource.RLIMIT_AS, (vm + 200 * 2**20, resource.RLIM_INFINITY))  # two slabs need 281 MB
r = L.hub_overlap_report(max_reports=1)
print("result", free["verified"], free["overlap_count"], r["verified"], r["overlap_count"])
"""
    line = run_limited(code)
    assert line.startswith("result"), line
    _, free_verified, free_count, verified, count = line.split()
    assert free_verified == "True" and verified == "True", line
    assert int(count) == int(free_count) > 0, line


def test_a_group_of_hubs_too_large_for_memory_is_refused_before_its_fuse():
    """Groups of hubs built as one have no size limit (their Fuse reports progress and stops at a cancel), but one
    whose Fuse would not fit in memory is refused before it starts: a 16 x 16 x 16 block of overlapping balls (their
    beams inside them) is one group of 4,096 hubs, a face each at 1 MB (4.3 GB), under an address space of 2 GB."""
    code = ("report(lambda: sl.Lattice([((0, 0, 0), 0.55)], [(0, 1, 0, 0, 0, 0.1, 0.1)], (16, 16, 16), *T).brep())")
    message = run_limited(code, 2 * GIB)
    assert message.startswith("MemoryError: "), message
    assert re.search(r"OpenCASCADE's Fuse of 4096 hubs built as one \(1 group\)", message), message
    estimate, budget, _ = figures(message)
    assert estimate > budget


def test_a_mesh_group_too_large_for_memory_is_refused_before_its_union():
    """The mesh unites groups of any size too (pairwise exact unions, a cancel checked between two), but a group
    whose exact union would not fit is refused before it starts: the same 4,096 overlapping balls as a mesh, about
    4 KB per triangle of their templates, under an address space of 2 GB."""
    code = ("report(lambda: sl.Lattice([((0, 0, 0), 0.55)], [(0, 1, 0, 0, 0, 0.1, 0.1)], (16, 16, 16), *T)"
            ".to_mesh(0.005))")
    message = run_limited(code, 2 * GIB)
    assert message.startswith("MemoryError: "), message
    assert re.search(r"the exact union of 4096 hubs joined in one group \(\d+ triangles", message), message
    estimate, budget, _ = figures(message)
    assert estimate > budget
