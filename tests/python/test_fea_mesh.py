"""Issue 14, item 5: a LatticePart's STEP is meshable for analysis by a tool we did not write. gmsh (Debian's
python3-gmsh) imports the STEP assembly of a small crowded part (the main job's twisted, tapered octet in a box,
with a skin), makes the skin and the lattice conformal (fragment), and meshes them into tetrahedra; the mesh's
volume agrees with the exact volume within the chord error of its size. docs/fea.md shows the same steps.
"""
import os

import gmsh
import pytest

import steadylattice as sl
from gmsh_parts import box_brep, tetrahedra_volume  # tests/common, on the path from conftest.py

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "kernel", "data")


@pytest.fixture
def gmsh_session():
    gmsh.initialize(readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    yield gmsh
    gmsh.finalize()


def test_gmsh_meshes_a_crowded_skinned_part_from_its_step(gmsh_session, tmp_path):
    with open(os.path.join(DATA, "main_job_octet.json")) as f:
        lattice = sl.Lattice.from_json(f.read())
    body = box_brep(str(tmp_path), (11.5, 11.5, 7.5), (17.0, 17.0, 13.0))
    step = str(tmp_path / "part.step")
    stats = {}
    lattice.write_step(step, body=body, skin=1.0, stats=stats)
    written = sl.read_step(step)
    assert [p["solids"] for p in written] == [1, 1], stats  # lattice and skin, one solid each
    assert stats["inside_hubs"] > 0 and stats["crossing_hubs"] > 0, stats
    exact = sum(p["volume"] for p in written)

    gmsh.model.add("part")
    gmsh.model.occ.importShapes(step)
    volumes = gmsh.model.occ.getEntities(3)
    assert len(volumes) == 2
    # Skin and lattice meet on faces of the inner wall; fragmenting shares those faces, so the mesh is conformal.
    gmsh.model.occ.fragment(volumes[:1], volumes[1:])
    gmsh.model.occ.synchronize()
    shared = [s for _, s in gmsh.model.getEntities(2) if len(gmsh.model.getAdjacencies(2, s)[0]) == 2]
    assert shared, "the skin and the lattice share no surface after fragment"
    gmsh.option.setNumber("Mesh.MeshSizeMax", 1.0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 12)  # elements per 2 pi of curvature
    gmsh.model.mesh.generate(3)
    count, volume = tetrahedra_volume()
    assert count > 10000
    # Chords of 12 segments a turn lose about 1 % of a beam's cross-section; measured 0.69 %.
    assert abs(volume - exact) < 0.02 * exact, (volume, exact)


def test_gmsh_meshes_the_part_as_one_solid_from_its_step(gmsh_session, tmp_path):
    """write_step(united=True): the lattice united with its skin, one solid (one material), meshed without a
    fragment; the main job meshes this way (tests/bench/bench_gmsh_main_job.py --long), where its assembly does not."""
    with open(os.path.join(DATA, "main_job_octet.json")) as f:
        lattice = sl.Lattice.from_json(f.read())
    body = box_brep(str(tmp_path), (11.5, 11.5, 7.5), (17.0, 17.0, 13.0))
    step = str(tmp_path / "part.step")
    lattice.write_step(step, body=body, skin=1.0, united=True, lattice_name="Part")
    written = sl.read_step(step)
    assert [(p["name"], p["solids"], p["valid"]) for p in written] == [("Part", 1, True)]
    united = sl.brep_properties(lattice.brep(body, skin=1.0))
    assert abs(written[0]["volume"] - united["volume"]) < 1e-6 * united["volume"]

    gmsh.model.add("part")
    gmsh.model.occ.importShapes(step)
    gmsh.model.occ.synchronize()
    assert len(gmsh.model.getEntities(3)) == 1
    gmsh.option.setNumber("Mesh.MeshSizeMax", 1.0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 12)
    gmsh.model.mesh.generate(3)
    count, volume = tetrahedra_volume()
    assert count > 10000
    assert abs(volume - united["volume"]) < 0.02 * united["volume"], (volume, united["volume"])
