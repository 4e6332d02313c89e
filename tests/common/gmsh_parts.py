"""gmsh as the independent tool of the FEA test and benchmark: a box body made by gmsh's own OpenCASCADE, and the
count and volume of the linear tetrahedra it meshed. Both need an initialized gmsh session."""
import os

import gmsh
import numpy as np


def box_brep(folder, corner, size):
    """A box body as BREP text, written by gmsh into `folder`."""
    gmsh.model.add("body")
    gmsh.model.occ.addBox(*corner, *size)
    gmsh.model.occ.synchronize()
    path = os.path.join(folder, "box.brep")
    gmsh.write(path)
    gmsh.model.remove()
    with open(path) as f:
        return f.read()


def tetrahedra_volume():
    """Number and summed volume of the current model's linear tetrahedra (gmsh element type 4)."""
    tags, coords, _ = gmsh.model.mesh.getNodes()
    coords = np.asarray(coords).reshape(-1, 3)
    where = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    where[tags] = np.arange(len(tags))
    count, volume = 0, 0.0
    for kind, _, nodes in zip(*gmsh.model.mesh.getElements(3)):
        if kind != 4:
            raise ValueError("gmsh made elements of type %d; only linear tetrahedra (4) were asked for" % kind)
        t = where[np.asarray(nodes, dtype=np.int64).reshape(-1, 4)]
        a, b, c, d = (coords[t[:, i]] for i in range(4))
        volume += np.abs(np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a)).sum() / 6.0
        count += len(t)
    return count, volume
