"""The main job's part meshed for analysis by gmsh (Debian's python3-gmsh): the STEP assembly the kernel writes
(lattice and skin, two solids), imported by gmsh's OpenCASCADE, fragmented so the skin and the lattice share their
faces (a conformal mesh), meshed into linear tetrahedra. Prints the STEP's size, gmsh's import, fragment and
meshing times, the tetrahedra and the mesh's volume against the exact volume (the kernel's adaptive integration).
Uses out/lattice_part.step when the main job has run (scripts/install.sh), else writes it first (about 90 s).
Usage: bench_gmsh_main_job.py [mesh size in mm, default 1.0]"""
import os
import sys
import tempfile
import time

import gmsh
import numpy as np

import steadylattice as sl

SOURCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def main_job_step():
    saved = os.path.join(SOURCE, "out", "lattice_part.step")
    if os.path.exists(saved):
        return saved, None, None
    data = os.path.join(SOURCE, "tests", "kernel", "data")
    with open(os.path.join(data, "main_job_octet.json")) as f:
        lattice = sl.Lattice.from_json(f.read())
    with open(os.path.join(data, "main_job_cylinder.brep")) as f:
        body = f.read()
    path = os.path.join(tempfile.mkdtemp(), "lattice_part.step")
    stats = {}
    start = time.time()
    lattice.write_step(path, body=body, skin=1.2, stats=stats)
    return path, time.time() - start, stats


def tetrahedra():
    tags, coords, _ = gmsh.model.mesh.getNodes()
    coords = np.asarray(coords).reshape(-1, 3)
    where = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    where[tags] = np.arange(len(tags))
    count, volume = 0, 0.0
    for _, _, nodes in zip(*gmsh.model.mesh.getElements(3)):
        t = where[np.asarray(nodes, dtype=np.int64).reshape(-1, 4)]
        a, b, c, d = (coords[t[:, i]] for i in range(4))
        volume += np.abs(np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a)).sum() / 6.0
        count += len(t)
    return count, volume


def main():
    size = float(sys.argv[1]) if len(sys.argv) > 1 and not sys.argv[1].startswith("--") else 1.0
    step, write_seconds, stats = main_job_step()
    parts = sl.read_step(step)
    exact = sum(p["volume"] for p in parts)
    print("main job STEP: %.1f MB, %s; parts %s%s" % (
        os.path.getsize(step) / 1e6, "written in %.1f s" % write_seconds if write_seconds else "from the main job",
        ", ".join("%s: %d solid(s), %s" % (p["name"], p["solids"], "valid" if p["valid"] else "INVALID")
                  for p in parts),
        "; %d loose pieces given to the skin" % stats["skin_pieces"] if stats else ""))
    gmsh.initialize(readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    start = time.time()
    gmsh.model.occ.importShapes(step)
    imported = time.time() - start
    start = time.time()
    volumes = gmsh.model.occ.getEntities(3)
    gmsh.model.occ.fragment(volumes[:1], volumes[1:])
    gmsh.model.occ.synchronize()
    fragmented = time.time() - start
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 12)
    start = time.time()
    gmsh.model.mesh.generate(3)
    meshed = time.time() - start
    count, volume = tetrahedra()
    gmsh.finalize()
    print("gmsh %s: import %.1f s, fragment %.1f s, mesh (size %g mm, 12 a turn) %.1f s: %d tetrahedra, volume %.2f "
          "mm^3 against the exact %.2f (%+.2f %%)" % (gmsh.__version__, imported, fragmented, size, meshed, count,
                                                      volume, exact, 100.0 * (volume / exact - 1.0)))


if __name__ == "__main__":
    main()
