// Issue 16, item 5: the same input gives byte-identical outputs whatever the number of threads. Every output the
// kernel writes is made on 1, 2 and 8 threads (an arena of that many, more threads than this machine's cores for
// 8) and compared byte for byte: the lattice file, the trimmed and skinned part's BREP text and its STEP assembly,
// the mesh's arrays, binary STL, 3MF with the mesh and with the beam lattice, and the properties to the last bit.
// The lattice is crowded (the octet preset with beams 0.8 of its nodes) and clipped by a tilted cylinder, so the
// parallel phases (clean check, hub catalogue, templates, trimming classification) all have work to share.
#include <gtest/gtest.h>

#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Builder.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <gp_Ax2.hxx>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "brep/canonical_order.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/brep/lattice_part.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice_io.hpp"
#include "steady/lattice/presets.hpp"
#include "steady/mesh/lattice_mesh.hpp"
#include "steady/mesh/mesh_files.hpp"
#include "steady/properties/lattice_properties.hpp"
#include "test_support.hpp"

namespace steady {
namespace {

template <class T>
std::string raw_bytes(const T* data, std::size_t count) {
  return std::string(reinterpret_cast<const char*>(data), count * sizeof(T));
}

// Every output of `lattice` (and of its part in `body`), by name, made on `threads` threads.
std::map<std::string, std::string> outputs_on(int threads, const Lattice& lattice, const std::string& body) {
  tbb::global_control allow(tbb::global_control::max_allowed_parallelism, threads);
  tbb::task_arena arena(threads);
  std::map<std::string, std::string> out;
  arena.execute([&] {
    const std::string dir = testing::TempDir() + "/determinism_" + std::to_string(getpid()) + "_" + std::to_string(threads);
    const FlatLattice flat = flatten(lattice);
    out["json"] = lattice_to_json(lattice);
    LatticePartRequest request;
    request.body_brep = body;
    request.trim.skin = 0.3;
    out["part brep"] = lattice_part_brep(flat, request);
    write_lattice_step(dir + ".step", flat, request);
    out["part step"] = test::file_bytes(dir + ".step");
    const TriangleMesh mesh = lattice_mesh(flat, MeshOptions{0.02});
    out["mesh vertices"] = raw_bytes(mesh.vertices.data(), mesh.vertices.size());
    out["mesh triangles"] = raw_bytes(mesh.triangles.data(), mesh.triangles.size());
    write_stl(mesh, dir + ".stl");
    out["stl"] = test::file_bytes(dir + ".stl");
    write_3mf(mesh, dir + ".3mf");
    out["3mf"] = test::file_bytes(dir + ".3mf");
    BeamLatticeOptions beams;
    beams.representation = &mesh;
    write_3mf_beam_lattice(flat, dir + "_beams.3mf", beams);
    out["3mf beam lattice"] = test::file_bytes(dir + "_beams.3mf");
    const LatticeProperties p = lattice_properties(lattice);
    const double numbers[] = {p.volume,        p.area,          p.centroid.x,    p.centroid.y,    p.centroid.z,
                              p.inertia[0][0], p.inertia[1][1], p.inertia[2][2], p.inertia[0][1], p.inertia[1][2]};
    out["properties"] = raw_bytes(numbers, sizeof numbers / sizeof numbers[0]);
    for (const char* suffix : {".step", ".stl", ".3mf", "_beams.3mf"}) std::remove((dir + suffix).c_str());
  });
  return out;
}

TEST(Determinism, EveryOutputIsTheSameBytesOnOneTwoAndEightThreads) {
  const Lattice lattice = preset_lattice("octet", {3, 3, 2}, 4.0, 0.5, 0.4);
  gp_Ax2 axis(gp_Pnt(6.0, 6.0, -1.0), gp_Dir(0.2, 0.1, 1.0));
  const std::string body = brep_to_text(BRepPrimAPI_MakeCylinder(axis, 5.0, 10.0).Shape());
  const std::map<std::string, std::string> one = outputs_on(1, lattice, body);
  for (const auto& [name, bytes] : one) EXPECT_GT(bytes.size(), 8u) << name << " is empty";
  for (int threads : {2, 8}) {
    const std::map<std::string, std::string> other = outputs_on(threads, lattice, body);
    ASSERT_EQ(other.size(), one.size());
    for (const auto& [name, bytes] : one)
      EXPECT_TRUE(other.at(name) == bytes) << name << " differs between 1 and " << threads << " threads ("
                                           << bytes.size() << " and " << other.at(name).size() << " bytes)";
  }
}

TEST(Determinism, AShellInCanonicalOrderDoesNotDependOnTheOrderItCameIn) {
  // What BRepOffset's address-ordered output needs: the same faces in any order, each wire starting at any edge,
  // give the same shell, and it stays a valid solid of the same volume.
  const TopoDS_Shape cylinder = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(1, 2, 3), gp_Dir(0.3, 0.2, 1.0)), 2.0, 5.0).Shape();
  const TopoDS_Shell shell = TopoDS::Shell(TopExp_Explorer(cylinder, TopAbs_SHELL).Current());
  std::vector<TopoDS_Shape> faces;
  for (TopoDS_Iterator it(shell); it.More(); it.Next()) faces.push_back(it.Value());
  const BRep_Builder b;
  auto solid_of = [&](const TopoDS_Shell& s) {
    TopoDS_Solid solid;
    b.MakeSolid(solid);
    b.Add(solid, s);
    return solid;
  };
  std::string first;
  for (int turn = 0; turn < 3; ++turn) {
    TopoDS_Shell shuffled = TopoDS::Shell(shell.EmptyCopied());
    for (std::size_t k = 0; k < faces.size(); ++k) b.Add(shuffled, faces[(k + turn) % faces.size()]);
    shuffled.Closed(Standard_True);
    const TopoDS_Solid solid = solid_of(in_canonical_order(shuffled));
    EXPECT_TRUE(is_valid(solid)) << validity_report(solid, 3);
    EXPECT_NEAR(shape_volume(solid), shape_volume(cylinder), 1e-9 * shape_volume(cylinder));
    const std::string text = brep_to_text(solid);
    if (turn == 0) first = text;
    EXPECT_TRUE(text == first) << "the order of the faces given changed the canonical shell (turn " << turn << ")";
  }
  // Without it, the texts differ: the test can see an order.
  TopoDS_Shell turned = TopoDS::Shell(shell.EmptyCopied());
  for (std::size_t k = 0; k < faces.size(); ++k) b.Add(turned, faces[(k + 1) % faces.size()]);
  EXPECT_NE(brep_to_text(solid_of(turned)), brep_to_text(solid_of(shell)));
}

}  // namespace
}  // namespace steady
