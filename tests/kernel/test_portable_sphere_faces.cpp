// Sphere faces whose loops cross the seam (as OpenCASCADE's Booleans leave them) rebuilt on a portable frame: the
// same solid, valid, and a STEP file of it that reads back valid, where the face as the Boolean left it reads back
// with intersecting wires.
#include <gtest/gtest.h>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepTools_ReShape.hxx>
#include <BRep_Tool.hxx>
#include <Geom_SphericalSurface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>

#include <filesystem>
#include <random>
#include <string>

#include <unistd.h>

#include "brep/portable_sphere_faces.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/brep/step_assembly.hpp"
#include "steady/brep/trim.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice_io.hpp"
#include "test_support.hpp"

namespace steady {
namespace {

int straddling_faces(const TopoDS_Shape& shape) {
  int n = 0;
  for (TopExp_Explorer f(shape, TopAbs_FACE); f.More(); f.Next()) n += has_chain_across_seam(TopoDS::Face(f.Current()));
  return n;
}

struct ReadBack {
  int solids = 0, invalid = 0;
  double volume = 0.0;
};

// The shape through a STEP file (the kernel's writer, OpenCASCADE's reader in a process of its own).
ReadBack through_step(const TopoDS_Shape& shape, const std::string& name, const TopoDS_Shape& beside = {}) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("steady_portable_" + std::to_string(::getpid()) + "_" + name + ".step")).string();
  std::vector<StepPart> parts = {{"Part", shape}};
  if (!beside.IsNull()) parts.push_back({"Beside", beside});
  write_step_assembly(path, parts);
  ReadBack out;
  const std::vector<StepPart> back = read_step_parts(path);
  for (const StepPart& part : {back.front()})
    for (TopExp_Explorer s(part.shape, TopAbs_SOLID); s.More(); s.Next()) {
      ++out.solids;
      out.invalid += !BRepCheck_Analyzer(s.Current()).IsValid();
      out.volume += shape_volume(s.Current());
    }
  std::filesystem::remove(path);
  return out;
}

TopoDS_Shape reseated(const TopoDS_Shape& shape, PortableSphereFaces& report) {
  Handle(BRepTools_ReShape) reshape = new BRepTools_ReShape;
  reshape->ModeConsiderLocation() = Standard_True;
  report = reseat_sphere_faces(shape, *reshape);
  return reshape->Apply(shape);
}

// Checks `shape` (with `expected` straddling sphere faces) before and after: the STEP of the reseated shape reads
// back valid with the same volume, where (when `fails_before`) the shape as it was reads back invalid.
PortableSphereFaces expect_portable(const TopoDS_Shape& shape, int expected, bool fails_before,
                                    const std::string& name, const TopoDS_Shape& beside = {}) {
  EXPECT_TRUE(BRepCheck_Analyzer(shape).IsValid()) << name;
  EXPECT_EQ(straddling_faces(shape), expected) << name;
  if (straddling_faces(shape) != expected) return {};
  if (fails_before) {
    const ReadBack before = through_step(shape, name + "_before", beside);
    EXPECT_GT(before.invalid, 0) << name << ": the face as the Boolean left it should read back invalid";
  }
  PortableSphereFaces report;
  const TopoDS_Shape after = reseated(shape, report);
  EXPECT_EQ(report.reseated, expected) << name << ": " << report.kept_reason;
  EXPECT_EQ(report.kept, 0) << name << ": " << report.kept_reason;
  EXPECT_TRUE(BRepCheck_Analyzer(after).IsValid()) << name;
  EXPECT_EQ(straddling_faces(after), 0) << name;
  const double volume = shape_volume(shape);
  // The new (u, v) curves follow the edges' 3D curves, which lie on the sphere only to the edges' tolerance (the
  // Booleans' intersection curves: 1e-7 here): the volumes integrated along them differ by up to 2e-8.
  EXPECT_NEAR(shape_volume(after) / volume, 1.0, 1e-7) << name;
  const ReadBack back = through_step(after, name + "_after", beside);
  EXPECT_EQ(back.solids, 1) << name;
  EXPECT_EQ(back.invalid, 0) << name;
  EXPECT_NEAR(back.volume / volume, 1.0, 1e-6) << name;
  return report;
}

// The sweep's cubic lattice with a bend in the tilted cylinder, skin 0.3 (tests/python/crowded_sweep.py): its
// lattice part, as the trim leaves it, has two sphere faces cut by the inner wall across their seams. One of them
// (a hub cut by the wall's bottom, four holes, no seam fits between them) read back from STEP with intersecting
// wires; rebuilt, both read back valid. The second needs a seam through two of its holes (a crossing frame).
TEST(PortableSphereFaces, TheLatticePartOfACubicLatticeInASkinnedCylinderReadsBackValid) {
  const std::string data = std::string(STEADY_TEST_DATA);
  const FlatLattice f = flatten(lattice_from_json(test::file_bytes(data + "/cubic_bend_skinned_straddle.json")));
  TrimOptions options;
  options.skin = 0.3;
  options.unite_skin = false;  // the assembly: the lattice part apart from the skin
  const TopoDS_Shape body = brep_from_text(test::file_bytes(data + "/../../python/data/cylinder.brep"), "body");
  const TrimResult trimmed = trim_lattice(f, body, options);
  EXPECT_EQ(expect_portable(trimmed.lattice, 2, true, "cubic_in_cylinder", trimmed.skin).seam_through_loops, 1);
}

// A cubic hub: holes around the six axes (37 degrees each), the one around +x across OpenCASCADE's seam (the half
// plane y = 0, x > 0), the poles inside the holes around +-z. No seam fits between the holes: the new one crosses
// the loops around its poles once each.
TEST(PortableSphereFaces, ACubicHubWithNoRoomBetweenItsHolesGetsASeamThroughTwoOfThem) {
  TopoDS_Shape hub = BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 0), 1.0).Shape();
  const gp_Dir axes[] = {gp::DX(), gp::DY(), gp::DZ()};
  for (const gp_Dir& axis : axes) {
    const gp_Ax2 through(gp_Pnt(0, 0, 0).Translated(gp_Vec(axis) * -2.0), axis);
    hub = BRepAlgoAPI_Cut(hub, BRepPrimAPI_MakeCylinder(through, 0.6, 4.0).Shape()).Shape();
  }
  EXPECT_EQ(expect_portable(hub, 1, false, "cubic_hub").seam_through_loops, 1);
}

// Random cuts by boxes and cylinders of balls turned at random: whatever the Booleans leave, the reseated solid
// is valid, has no chain across a seam and reads back valid from STEP with its volume.
TEST(PortableSphereFaces, RandomCutBallsComeBackValidFromStep) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int straddled = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const gp_Dir z(unit(rng), unit(rng), unit(rng) + 0.01), x0(unit(rng), unit(rng), unit(rng) + 0.01);
    const gp_Ax2 frame(gp_Pnt(0, 0, 0), z, gp_Dir(gp_Vec(z).Crossed(gp_Vec(x0))));
    TopoDS_Shape ball = BRepPrimAPI_MakeSphere(frame, 1.0).Shape();
    for (int k = 0; k < 4; ++k) {
      const gp_Dir axis(unit(rng), unit(rng), unit(rng) + 0.01);
      const gp_Ax2 through(gp_Pnt(0, 0, 0).Translated(gp_Vec(axis) * 0.3), axis);
      ball = BRepAlgoAPI_Cut(ball, BRepPrimAPI_MakeCylinder(through, 0.25 + 0.3 * std::abs(unit(rng)), 3.0).Shape())
                 .Shape();
    }
    const int before = straddling_faces(ball);
    if (before == 0 || !BRepCheck_Analyzer(ball).IsValid()) continue;
    ++straddled;
    expect_portable(ball, before, false, "random_" + std::to_string(trial));
  }
  EXPECT_GE(straddled, 3) << "too few random cuts crossed the seam to test anything";
}

}  // namespace
}  // namespace steady
