"""A LatticePart meshed for analysis by gmsh (Debian's python3-gmsh): the STEP the kernel writes, imported by gmsh's
OpenCASCADE and meshed into linear tetrahedra. Prints the STEP's size, gmsh's import, fragment and meshing times,
the tetrahedra and the mesh's volume against the exact volume (the kernel's adaptive integration).
Default: the main job's octet in a 17 x 17 x 13 mm box with a 1 mm skin, as an assembly (lattice and skin, two
solids) fragmented so that they share their faces (a conformal mesh; what tests/python/test_fea_mesh.py meshes).
--long: the main job itself as one solid (write_step(united=True): the lattice united with its skin, one
material), about 60 s to write and 12 minutes to mesh; with --assembly, the main job's assembly fragmented instead
(it failed while beams grazing the skin's inner wall left the lattice lenses 0.037 mm thick; docs/fea.md).
A mesher's failure is printed and the exit status is 1.
Usage: bench_gmsh_main_job.py [--long [--assembly]] [mesh size in mm, default 1.0]"""
import os
import sys
import tempfile
import time

import gmsh

import steadylattice as sl

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from gmsh_parts import box_brep, tetrahedra_volume  # noqa: E402  (tests/common)

SOURCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def part_step(whole_job, united):
    """(STEP path, seconds to write it, trim stats) of the main job or of its small block."""
    data = os.path.join(SOURCE, "tests", "kernel", "data")
    with open(os.path.join(data, "main_job_octet.json")) as f:
        lattice = sl.Lattice.from_json(f.read())
    if whole_job:
        with open(os.path.join(data, "main_job_cylinder.brep")) as f:
            body, skin = f.read(), 1.2
    else:
        body, skin = box_brep(tempfile.mkdtemp(), (11.5, 11.5, 7.5), (17.0, 17.0, 13.0)), 1.0
    path = os.path.join(tempfile.mkdtemp(), "lattice_part.step")
    stats = {}
    start = time.time()
    lattice.write_step(path, body=body, skin=skin, stats=stats, united=united)
    return path, time.time() - start, stats


def main():
    whole_job = "--long" in sys.argv
    united = whole_job and "--assembly" not in sys.argv
    sizes = [a for a in sys.argv[1:] if not a.startswith("--")]
    size = float(sizes[0]) if sizes else 1.0
    gmsh.initialize(readConfigFiles=False)  # box_brep uses the session
    gmsh.option.setNumber("General.Terminal", 0)
    step, write_seconds, stats = part_step(whole_job, united)
    parts = sl.read_step(step)
    exact = sum(p["volume"] for p in parts)
    what = ("main job" if whole_job else "main job's octet in a 17 mm box") + (
        " as one solid" if united else ", lattice and skin")
    print("%s STEP: %.1f MB, written in %.1f s; parts %s%s" % (
        what, os.path.getsize(step) / 1e6, write_seconds,
        ", ".join("%s: %d solid(s), %s" % (p["name"], p["solids"], "valid" if p["valid"] else "INVALID")
                  for p in parts),
        "; %d pieces given to the skin (%d of them lenses of grazing beams)"
        % (stats["skin_pieces"], stats["grazing_pieces"]) if not united else ""))
    start = time.time()
    gmsh.model.occ.importShapes(step)
    imported = time.time() - start
    start = time.time()
    volumes = gmsh.model.occ.getEntities(3)
    if len(volumes) > 1:  # lattice and skin: shared faces, so that the mesh is conformal
        gmsh.model.occ.fragment(volumes[:1], volumes[1:])
    gmsh.model.occ.synchronize()
    fragmented = time.time() - start
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 12)
    start = time.time()
    try:
        gmsh.model.mesh.generate(3)
    except Exception as failure:  # gmsh raises a bare Exception with its last error
        print("gmsh %s: import %.1f s, fragment %.1f s, meshing FAILED after %.1f s: %s"
              % (gmsh.__version__, imported, fragmented, time.time() - start, failure))
        gmsh.finalize()
        return 1
    meshed = time.time() - start
    count, volume = tetrahedra_volume()
    gmsh.finalize()
    print("gmsh %s: import %.1f s, fragment %.1f s, mesh (size %g mm, 12 a turn) %.1f s: %d tetrahedra, volume %.2f "
          "mm^3 against the exact %.2f (%+.2f %%)" % (gmsh.__version__, imported, fragmented, size, meshed, count,
                                                      volume, exact, 100.0 * (volume / exact - 1.0)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
