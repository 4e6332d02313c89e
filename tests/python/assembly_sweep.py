"""Issue 14's sweep of skinned assemblies: crowded_sweep's lattices (6 presets, no step, a bend and a screw; node
0.2, beam/node 0.6, 3 x 3 x 4 cells) in the tilted cylinder of the Python tests with skins 0.1, 0.2 and 0.3.

Each case writes the STEP assembly (lattice and skin as two parts), reads it back with OpenCASCADE's reader and
checks that both parts are valid and one solid each, and that their volumes add up to the united part's (brep()
with the same skin) to 1e-6. `python3 assembly_sweep.py` prints every case (with the lenses split off for the skin,
the sphere faces rebuilt on a portable frame and the united part's loosest edge) and the counts; about 10
minutes. test_brep.py runs three cases.
"""
import os
import sys
import tempfile
import time

import steadylattice as sl

from crowded_sweep import PRESETS, lattice

BODY = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "cylinder.brep")
SUM_TOLERANCE = 1e-6


def run_case(preset, step, skin, body):
    """(outcome, detail, stats of write_step): outcome 'ok', 'invalid' (a part read back invalid or in pieces),
    'apart' (the parts do not add up to the united part) or 'error'."""
    lat = lattice(preset, 0.2, 0.6, step, (3, 3, 4))
    path = os.path.join(tempfile.mkdtemp(), "assembly.step")
    stats = {}
    try:
        lat.write_step(path, body=body, skin=skin, stats=stats)
        parts = sl.read_step(path)
        united_properties = sl.brep_properties(lat.brep(body, skin=skin))
    except (ValueError, RuntimeError) as error:
        return "error", str(error)[:200], stats
    finally:
        if os.path.exists(path):
            os.remove(path)
    total, united = sum(p["volume"] for p in parts), united_properties["volume"]
    stats["sum_relative"] = (total - united) / united
    stats["united_loosest_edge"] = united_properties["max_edge_tolerance"]
    detail = "%s; lenses %d, faces reseated %d (kept %d); sum %.9f, united %.9f (%.1e); loosest edge %.1e" % (
        ", ".join("%s %d solid(s) %s" % (p["name"], p["solids"], "valid" if p["valid"] else "INVALID")
                  for p in parts),
        stats["grazing_pieces"], stats["reseated_sphere_faces"], stats["kept_straddling_faces"], total, united,
        (total - united) / united, united_properties["max_edge_tolerance"])
    if not all(p["valid"] and p["solids"] == 1 for p in parts):
        return "invalid", detail, stats
    if abs(total - united) > SUM_TOLERANCE * united:
        return "apart", detail, stats
    return "ok", detail, stats


def sweep(out=sys.stdout):
    with open(BODY) as f:
        body = f.read()
    counts = {"ok": 0, "invalid": 0, "apart": 0, "error": 0}
    for preset in PRESETS:
        for step in ("none", "bend", "screw"):
            for skin in (0.1, 0.2, 0.3):
                start = time.perf_counter()
                outcome, detail, _ = run_case(preset, step, skin, body)
                counts[outcome] += 1
                print("%-8s %-6s skin %.1f %-8s %6.1f s  %s" % (preset, step, skin, outcome,
                                                               time.perf_counter() - start, detail),
                      file=out, flush=True)
    print("cases %d: %s" % (sum(counts.values()), ", ".join("%s %d" % kv for kv in counts.items())), file=out,
          flush=True)
    return counts


if __name__ == "__main__":
    sweep()
