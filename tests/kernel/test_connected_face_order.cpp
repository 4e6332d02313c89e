// Shells written with their faces in connected order (brep/connected_face_order.hpp): OpenCASCADE's STEP reader
// orients a shell by scanning its remaining faces from the first after each face it adds, so a shell whose faces
// come in an arbitrary order reads back in quadratic time. The function, and the order of the faces the STEP
// writer puts in the file, are checked here.
#include <gtest/gtest.h>

#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRep_Builder.hxx>
#include <GProp_GProps.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

#include "brep/connected_face_order.hpp"
#include "steady/brep/brep_builder.hpp"
#include "steady/brep/step_assembly.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "test_lattices.hpp"
#include "test_support.hpp"

namespace steady {
namespace {

// Index of the first face (after the first) that shares no edge with any face before it, or -1 when none.
template <class EdgesOfFace>
long first_face_not_connected(std::size_t faces, EdgesOfFace edges_of) {
  std::set<long> seen;
  for (std::size_t i = 0; i < faces; ++i) {
    const std::vector<long> edges = edges_of(i);
    const bool touches = std::any_of(edges.begin(), edges.end(), [&](long e) { return seen.count(e) > 0; });
    if (i > 0 && !touches) return static_cast<long>(i);
    seen.insert(edges.begin(), edges.end());
  }
  return -1;
}

std::vector<TopoDS_Shape> faces_of(const TopoDS_Shape& shell) {
  std::vector<TopoDS_Shape> out;
  for (TopoDS_Iterator it(shell); it.More(); it.Next()) out.push_back(it.Value());
  return out;
}

long first_unconnected_face(const TopoDS_Shape& shell) {
  const std::vector<TopoDS_Shape> faces = faces_of(shell);
  return first_face_not_connected(faces.size(), [&](std::size_t i) {
    std::vector<long> edges;
    for (TopExp_Explorer x(faces[i], TopAbs_EDGE); x.More(); x.Next())
      edges.push_back(reinterpret_cast<long>(x.Current().TShape().get()));
    return edges;
  });
}

double volume(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props);
  return props.Mass();
}

// A BCC lattice's solid, its faces put in a shuffled order.
TopoDS_Solid shuffled_lattice_solid() {
  std::mt19937_64 rng(7);
  const TopoDS_Shape built = build_lattice_brep(flatten(test::bcc_lattice(rng, {3, 3, 3}))).shape;
  TopExp_Explorer solids(built, TopAbs_SOLID);
  TopExp_Explorer shells(solids.Current(), TopAbs_SHELL);
  std::vector<TopoDS_Shape> faces = faces_of(shells.Current());
  std::shuffle(faces.begin(), faces.end(), rng);
  const BRep_Builder b;
  TopoDS_Shell shell;
  b.MakeShell(shell);
  for (const TopoDS_Shape& f : faces) b.Add(shell, f);
  shell.Closed(true);
  TopoDS_Solid solid;
  b.MakeSolid(solid);
  b.Add(solid, shell);
  return solid;
}

TEST(ConnectedFaceOrder, EveryFaceOfAShellSharesAnEdgeWithOneBeforeIt) {
  const TopoDS_Solid shuffled = shuffled_lattice_solid();
  ASSERT_TRUE(BRepCheck_Analyzer(shuffled).IsValid());
  const TopoDS_Shape shuffled_shell = TopoDS_Iterator(shuffled).Value();
  ASSERT_GT(first_unconnected_face(shuffled_shell), 0) << "the shuffle left the faces connected: nothing is tested";

  const TopoDS_Shape ordered = with_faces_in_connected_order(shuffled);
  ASSERT_EQ(ordered.ShapeType(), TopAbs_SOLID);
  const TopoDS_Shape ordered_shell = TopoDS_Iterator(ordered).Value();
  EXPECT_EQ(first_unconnected_face(ordered_shell), -1);
  EXPECT_TRUE(ordered_shell.Closed());
  // The same faces, each with its orientation: a set of (TShape, orientation), and the same solid.
  std::set<std::pair<const void*, int>> before, after;
  for (const TopoDS_Shape& f : faces_of(shuffled_shell)) before.emplace(f.TShape().get(), f.Orientation());
  for (const TopoDS_Shape& f : faces_of(ordered_shell)) after.emplace(f.TShape().get(), f.Orientation());
  EXPECT_EQ(before, after);
  EXPECT_TRUE(BRepCheck_Analyzer(ordered).IsValid());
  EXPECT_NEAR(volume(ordered), volume(shuffled), 1e-12 * volume(shuffled));
}

TEST(ConnectedFaceOrder, AReversedMovedSolidInACompoundKeepsItsPlaceAndSide) {
  const TopoDS_Solid shuffled = shuffled_lattice_solid();
  gp_Trsf move;
  move.SetTranslation(gp_Vec(5.0, -2.0, 1.0));
  const TopoDS_Shape moved = shuffled.Moved(TopLoc_Location(move));
  TopoDS_Compound both;
  const BRep_Builder b;
  b.MakeCompound(both);
  b.Add(both, shuffled);
  b.Add(both, moved.Reversed());
  const TopoDS_Shape ordered = with_faces_in_connected_order(both);
  std::vector<TopoDS_Shape> in, out;
  for (TopoDS_Iterator it(both); it.More(); it.Next()) in.push_back(it.Value());
  for (TopoDS_Iterator it(ordered); it.More(); it.Next()) out.push_back(it.Value());
  ASSERT_EQ(out.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(out[i].Orientation(), in[i].Orientation());
    EXPECT_TRUE(out[i].Location().IsEqual(in[i].Location()));
    EXPECT_NEAR(volume(out[i]), volume(in[i]), 1e-9 * std::abs(volume(in[i])));
    EXPECT_EQ(first_unconnected_face(TopoDS_Iterator(out[i]).Value()), -1);
  }
}

// The file itself: each CLOSED_SHELL lists its faces so that every face shares an EDGE_CURVE with one before it.
TEST(ConnectedFaceOrder, TheStepWriterListsEachShellsFacesInConnectedOrder) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("steady_face_order_" + std::to_string(::getpid()) + ".step")).string();
  write_step_assembly(path, {{"Lattice", shuffled_lattice_solid()}});
  const std::string text = test::file_bytes(path);
  std::remove(path.c_str());
  // Entities as "#id=TYPE(arguments);" (the writer may break a long one over lines).
  std::map<long, std::pair<std::string, std::string>> entities;
  const std::regex entity(R"(#(\d+)\s*=\s*([A-Z_0-9]+)\s*\(([^;]*)\)\s*;)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), entity); it != std::sregex_iterator(); ++it)
    entities[std::stol((*it)[1])] = {(*it)[2], (*it)[3]};
  const auto references = [](const std::string& args) {
    std::vector<long> ids;
    const std::regex ref(R"(#(\d+))");
    for (auto it = std::sregex_iterator(args.begin(), args.end(), ref); it != std::sregex_iterator(); ++it)
      ids.push_back(std::stol((*it)[1]));
    return ids;
  };
  // The EDGE_CURVEs reached from an entity through bounds, loops and oriented edges.
  const auto edge_curves = [&](long face) {
    std::vector<long> out, todo{face};
    while (!todo.empty()) {
      const long id = todo.back();
      todo.pop_back();
      const auto& [type, args] = entities.at(id);
      if (type == "EDGE_CURVE") {
        out.push_back(id);
        continue;
      }
      if (type != "ADVANCED_FACE" && type != "FACE_BOUND" && type != "FACE_OUTER_BOUND" && type != "EDGE_LOOP" &&
          type != "ORIENTED_EDGE")
        continue;
      for (long r : references(args)) todo.push_back(r);
    }
    return out;
  };
  int shells = 0;
  std::size_t faces = 0;
  for (const auto& [id, entity_text] : entities) {
    if (entity_text.first != "CLOSED_SHELL") continue;
    ++shells;
    const std::vector<long> shell_faces = references(entity_text.second);
    faces += shell_faces.size();
    EXPECT_EQ(first_face_not_connected(shell_faces.size(), [&](std::size_t i) { return edge_curves(shell_faces[i]); }),
              -1)
        << "CLOSED_SHELL #" << id;
  }
  EXPECT_EQ(shells, 1);
  EXPECT_GT(faces, 100u);
}

}  // namespace
}  // namespace steady
