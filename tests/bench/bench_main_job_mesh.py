"""The main job's part as a printable mesh: the kernel's trimmed, skinned mesh against FreeCAD's MeshPart on the
exact B-rep part, at the same measured deviation from the exact surface, in one run. Runs inside FreeCAD
(freecad -c); started by /usr/bin/python3 it reruns itself there.

For each tolerance both meshers start at it (ours as its chord tolerance, MeshPart as its linear deflection); the
deviation of each mesh from the exact part is measured (main_job_deviation.py), and whichever deviates more is given a
smaller tolerance until it deviates no more than the other. The times are medians of --runs runs at those
settings. The B-rep is built once in the run (end to end: B-rep + MeshPart against ours), unless --saved uses
out/lattice_part.FCStd (scripts/install.sh writes it) and skips that figure. Options (--runs N, --saved) reach
the rerun inside FreeCAD through the environment (STEADY_BENCH_RUNS, STEADY_BENCH_SAVED).
"""
import os
import statistics
import subprocess
import sys
import time

try:
    import FreeCAD
except ImportError:  # started by /usr/bin/python3: run again inside FreeCAD, with the checkout's workbench
    here = os.path.dirname(os.path.abspath(__file__))
    mod = os.path.join(here, "..", "..", "Mod", "LatticeWorkbench")
    env = dict(os.environ)
    if "--runs" in sys.argv:
        env["STEADY_BENCH_RUNS"] = sys.argv[sys.argv.index("--runs") + 1]
    if "--saved" in sys.argv:
        env["STEADY_BENCH_SAVED"] = "1"
    sys.exit(subprocess.call(["freecad", "-c", "-M", mod, os.path.abspath(__file__)], env=env))

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from main_job_deviation import ExactPart  # noqa: E402

SHRINK = 0.7  # a tolerance too coarse for equal deviation is lowered by this factor, a step at a time
STEPS = 6


def median_seconds(run, runs):
    times, result = [], None
    for _ in range(runs):
        start = time.time()
        result = run()
        times.append(time.time() - start)
    return statistics.median(times), times, result


def freecad_mesh_arrays(mesh):
    import numpy as np
    points, facets = mesh.Topology
    return np.array([(p.x, p.y, p.z) for p in points], dtype=float), np.array(facets, dtype=np.int64)


def checks(mesh):
    # each entry: two facet indices and the two ends of their intersection
    pairs = {tuple(sorted(p[:2])) for p in mesh.getSelfIntersections()} if mesh.hasSelfIntersections() else set()
    return ("solid %s, non-manifold %s, %d component(s), FreeCAD's approximate self-intersection test: %d pair(s)"
            % (mesh.isSolid(), mesh.hasNonManifolds(), mesh.countComponents(), len(pairs)))


class Ours:
    """The kernel's mesh of the part at a chord tolerance, from the part's definition (body tessellated by
    FreeCAD, its inner offset by OpenCASCADE)."""

    def __init__(self, part):
        from latticewb.kernel import mesh_export
        self.part, self.export = part, mesh_export

    def run(self, tolerance):
        lattice, body, inner, _ = self.export.part_meshes(self.part, tolerance)
        stats = {}
        vertices, triangles = lattice.to_mesh(tolerance, body=body, inner=inner, stats=stats)
        return vertices, triangles, stats


def meshpart(shape, deflection):
    import MeshPart
    return MeshPart.meshFromShape(Shape=shape, LinearDeflection=deflection, AngularDeflection=0.5, Relative=False)


def at_equal_deviation(exact, ours, shape, tolerance, runs, lines):
    import Mesh
    ours_tol, their_tol = tolerance, tolerance
    ours_dev = exact.deviation(*ours.run(ours_tol)[:2])
    their_dev = exact.deviation(*freecad_mesh_arrays(meshpart(shape, their_tol)))
    for _ in range(STEPS):  # the one that deviates more gets a finer tolerance
        if ours_dev > their_dev:
            ours_tol *= SHRINK
            ours_dev = exact.deviation(*ours.run(ours_tol)[:2])
        elif their_dev > ours_dev * 1.0001:
            their_tol *= SHRINK
            their_dev = exact.deviation(*freecad_mesh_arrays(meshpart(shape, their_tol)))
        else:
            break
    ours_s, ours_times, (vertices, triangles, stats) = median_seconds(lambda: ours.run(ours_tol), runs)
    their_s, their_times, theirs = median_seconds(lambda: meshpart(shape, their_tol), runs)
    path = "/tmp/bench_main_job_%d.stl" % os.getpid()
    lattice, body, inner, _ = ours.export.part_meshes(ours.part, ours_tol)
    lattice.write_stl(path, ours_tol, body=body, inner=inner)
    ours_mesh = Mesh.Mesh(path)
    os.remove(path)
    phases = ", ".join("%s %.2f" % (k[:-len("_seconds")], stats[k]) for k in
                       ("check_seconds", "template_seconds", "plan_seconds", "classify_seconds", "pieces_seconds",
                        "boolean_seconds", "join_seconds"))
    lines.append("tolerance %.2f mm:" % tolerance)
    lines.append("  ours     tolerance %.4f: %.3f s median of %s; %d triangles, measured deviation %.2e, volume %.1f"
                 % (ours_tol, ours_s, ", ".join("%.3f" % t for t in ours_times), len(triangles), ours_dev,
                    ours_mesh.Volume))
    lines.append("           phases (s): %s; band %d triangles" % (phases, stats["band_triangles"]))
    lines.append("           %s" % checks(ours_mesh))
    lines.append("  MeshPart deflection %.4f: %.3f s median of %s; %d facets, measured deviation %.2e, volume %.1f"
                 % (their_tol, their_s, ", ".join("%.3f" % t for t in their_times), theirs.CountFacets, their_dev,
                    theirs.Volume))
    lines.append("           %s" % checks(theirs))
    lines.append("  ratio at equal deviation: ours %.2fx MeshPart's speed" % (their_s / ours_s))
    return ours_s, their_s


def main():
    source = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    # the module of this build, not an older installed one
    sys.path.insert(0, os.environ.get("STEADY_BUILD_PYTHON", os.path.join(source, "build", "python")))
    from latticewb import api
    runs = int(os.environ.get("STEADY_BENCH_RUNS", "3"))
    saved = os.path.join(source, "out", "lattice_part.FCStd")
    if os.environ.get("STEADY_BENCH_SAVED") == "1" and os.path.exists(saved):
        doc = FreeCAD.openDocument(saved)
        part = [o for o in doc.Objects if api.get_type(o) == "LatticePart"][0]
        brep_seconds = None
    else:
        import importlib.util  # loaded under another name: as "main_job" the macro runs itself on import
        spec = importlib.util.spec_from_file_location("main_job_definition",
                                                      os.path.join(source, "examples", "main_job.py"))
        main_job = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(main_job)
        doc = FreeCAD.newDocument("MainJob")
        part = main_job.add_part(doc)
        start = time.time()
        doc.recompute()
        brep_seconds = time.time() - start
    exact = ExactPart(part)
    lines = ["main job: %d beams in a cylinder with a %.1f mm skin; exact B-rep volume %.1f mm^3%s"
             % (part.Lattice.BeamCount, exact.skin, part.Volume,
                "" if brep_seconds is None else ", B-rep built in %.1f s" % brep_seconds)]
    ours = Ours(part)
    for tolerance in (0.05, 0.01):
        ours_s, their_s = at_equal_deviation(exact, ours, part.Shape, tolerance, runs, lines)
        if brep_seconds is not None:
            lines.append("  end to end (B-rep %.1f s + MeshPart) against ours: %.1fx"
                         % (brep_seconds, (brep_seconds + their_s) / ours_s))
    FreeCAD.Console.PrintMessage("\n".join(lines) + "\n")
    print("\n".join(lines))


main()
