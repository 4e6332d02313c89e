"""The main job's part as a printable mesh: the kernel's trimmed, skinned mesh against FreeCAD's MeshPart on the
exact B-rep part, at the same chord tolerance (MeshPart's linear deflection), measured in one run. Runs inside
FreeCAD (freecad -c); tests/bench/run.sh starts it there. Uses out/lattice_part.FCStd when the main job has been
run (scripts/install.sh), else builds the B-rep part first (about 90 s)."""
import os
import subprocess
import sys
import time

try:
    import FreeCAD
except ImportError:  # started by /usr/bin/python3: run again inside FreeCAD, with the checkout's workbench
    here = os.path.dirname(os.path.abspath(__file__))
    mod = os.path.join(here, "..", "..", "Mod", "LatticeWorkbench")
    sys.exit(subprocess.call(["freecad", "-c", "-M", mod, os.path.abspath(__file__)] + sys.argv[1:]))


def mesh_checks(mesh):
    return "solid %s, non-manifold %s, facets %d" % (mesh.isSolid(), mesh.hasNonManifolds(), mesh.CountFacets)


def main():
    source = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    # the module of this build, not an older installed one
    sys.path.insert(0, os.environ.get("STEADY_BUILD_PYTHON", os.path.join(source, "build", "python")))
    import Mesh
    import MeshPart
    from latticewb import api
    from latticewb.kernel import mesh_export
    saved = os.path.join(source, "out", "lattice_part.FCStd")
    if os.path.exists(saved):
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
    lines = ["main job: %d beams in a cylinder with a 1.2 mm skin; exact B-rep volume %.1f mm^3%s"
             % (part.Lattice.BeamCount, part.Volume,
                "" if brep_seconds is None else ", B-rep built in %.1f s" % brep_seconds)]
    for tolerance in (0.05, 0.01):
        start = time.time()
        lattice, body, inner = mesh_export.part_meshes(part, tolerance)
        stats = {}
        vertices, triangles = lattice.to_mesh(tolerance, body=body, inner=inner, stats=stats)
        ours = time.time() - start
        path = "/tmp/bench_main_job.stl"
        lattice.write_stl(path, tolerance, body=body, inner=inner)
        ours_mesh = Mesh.Mesh(path)
        start = time.time()
        theirs = MeshPart.meshFromShape(Shape=part.Shape, LinearDeflection=tolerance, AngularDeflection=0.5,
                                        Relative=False)
        meshpart = time.time() - start
        lines.append("  tolerance %.2f mm: ours %.2f s (%d triangles, Booleans %.2f s on %d band triangles; %s, "
                     "volume %.1f)" % (tolerance, ours, len(triangles), stats["boolean_seconds"],
                                      stats["band_triangles"], mesh_checks(ours_mesh), ours_mesh.Volume))
        lines.append("                     MeshPart %.2f s (%s, volume %.1f); ratio %.1fx"
                     % (meshpart, mesh_checks(theirs), theirs.Volume, meshpart / ours))
    FreeCAD.Console.PrintMessage("\n".join(lines) + "\n")
    print("\n".join(lines))


main()
