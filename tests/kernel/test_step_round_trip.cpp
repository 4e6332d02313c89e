// Files the kernel writes, read back by OpenCASCADE's own readers (STEP through XCAF, BREP text): the same number
// of solids, each valid, each volume equal to the written one's. Crowded hubs are the hard case: spheres with 12
// holes whose circles, laid across the sphere's seam, came back from a STEP reader as intersecting wires.
#include <gtest/gtest.h>

#include <BRepBuilderAPI_Transform.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Tool.hxx>
#include <BRep_Builder.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_Curve.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>
#include <GProp_GProps.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <random>
#include <thread>

#include <unistd.h>

#include "test_lattices.hpp"
#include "test_support.hpp"
#include "brep/pcurve_pieces.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/brep/lattice_part.hpp"
#include "steady/brep/step_assembly.hpp"
#include "steady/brep/trim.hpp"
#include "steady/core/errors.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice_io.hpp"

namespace steady {
namespace {

std::string read_data(const std::string& name) { return test::file_bytes(std::string(STEADY_TEST_DATA) + "/" + name); }

// Volume by adaptive integration: the default Gauss rule is off by up to 2e-3 on a sphere face with 12 holes
// (the same face, laid out in two frames, measured 3.6479 and 3.6391), too coarse to compare two files.
double precise_volume(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props, 1e-9, Standard_True);
  return props.Mass();
}

std::vector<TopoDS_Shape> solids_of(const TopoDS_Shape& shape) {
  std::vector<TopoDS_Shape> out;
  for (TopExp_Explorer e(shape, TopAbs_SOLID); e.More(); e.Next()) out.push_back(e.Current());
  return out;
}

int invalid_faces(const TopoDS_Shape& shape) {
  int bad = 0;
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) bad += !BRepCheck_Analyzer(e.Current()).IsValid();
  return bad;
}

// Read-back `back` against written `written`: same solids, each valid, same volume to 1e-6 relative.
void expect_same_solids(const TopoDS_Shape& written, const TopoDS_Shape& back, const std::string& what) {
  const std::vector<TopoDS_Shape> a = solids_of(written), b = solids_of(back);
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < b.size(); ++i) {
    EXPECT_TRUE(BRepCheck_Analyzer(b[i]).IsValid()) << what << ": solid " << i << " read back invalid, "
                                                   << invalid_faces(b[i]) << " invalid faces";
  }
  const double va = precise_volume(written), vb = precise_volume(back);
  EXPECT_NEAR(vb / va, 1.0, 1e-6) << what << ": written " << va << ", read back " << vb;
}

// Edges of sphere faces whose (u, v) curve strays from their 3D curve by more than `limit`: a reader that
// drops a pcurve it cannot place rebuilds it by projection, cubic and up to 1e-2 off (the volume then drifts).
int strayed_sphere_pcurves(const TopoDS_Shape& shape, double limit, double* worst) {
  int strayed = 0;
  for (TopExp_Explorer f(shape, TopAbs_FACE); f.More(); f.Next()) {
    const TopoDS_Face& face = TopoDS::Face(f.Current());
    const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
    if (GeomAdaptor_Surface(surface).GetType() != GeomAbs_Sphere) continue;
    for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
      const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
      double a = 0, b = 0, c = 0, d = 0;
      const Handle(Geom_Curve) curve = BRep_Tool::Curve(edge, a, b);
      const Handle(Geom2d_Curve) pcurve = BRep_Tool::CurveOnSurface(edge, face, c, d);
      if (curve.IsNull() || pcurve.IsNull()) continue;
      double off = 0.0;
      for (int k = 0; k <= 64; ++k) {
        const double t = a + (b - a) * k / 64.0;
        const gp_Pnt2d uv = pcurve->Value(t);
        off = std::max(off, surface->Value(uv.X(), uv.Y()).Distance(curve->Value(t)));
      }
      *worst = std::max(*worst, off);
      strayed += off > limit;
    }
  }
  return strayed;
}

// Named after the process too: two test runs on one machine (two checkouts, a sanitizer build) must not share or
// remove each other's files.
std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("steady_round_trip_" + std::to_string(::getpid()) + "_" + name)).string();
}

// The main job's twisted, tapered octet (12 crowded beams a node) clipped by a box around its middle: interior
// hubs whole, boundary hubs cut.
TopoDS_Shape main_job_block() {
  const FlatLattice f = flatten(lattice_from_json(read_data("main_job_octet.json")));
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(9.5, 9.5, 5.5), gp_Pnt(30.5, 30.5, 22.5)).Shape();
  return trim_lattice(f, box, {}).part;
}

TEST(StepRoundTrip, CrowdedSpheresComeBackValidFromStep) {
  const TopoDS_Shape part = main_job_block();
  ASSERT_TRUE(is_valid(part));
  int twelve_hole_spheres = 0;
  for (TopExp_Explorer e(part, TopAbs_FACE); e.More(); e.Next()) {
    int wires = 0;
    for (TopExp_Explorer w(e.Current(), TopAbs_WIRE); w.More(); w.Next()) ++wires;
    twelve_hole_spheres += wires >= 12;
  }
  EXPECT_GT(twelve_hole_spheres, 10) << "the block should hold crowded spheres";
  const std::string path = temp_path("block.step");
  write_step_assembly(path, {{"Block", part}});
  const std::vector<StepPart> back = read_step_parts(path);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].name, "Block");
  expect_same_solids(part, back[0].shape, "main job block through STEP");
  // Every sphere edge comes back with the pcurve written (each edge carries its own piece of its circle's curve:
  // with the whole circle's, 14 of these 1,427 came back rebuilt, up to 1.2e-2 off).
  double worst = 0.0;
  EXPECT_EQ(strayed_sphere_pcurves(back[0].shape, 1e-6, &worst), 0) << "worst " << worst;
  std::printf("[ report ] main job block: %d spheres with 12 holes, STEP %.1f KB, sphere pcurves within %.1e\n",
              twelve_hole_spheres, std::filesystem::file_size(path) / 1024.0, worst);
  std::remove(path.c_str());
}

// One sphere face of the main job (tests/kernel/data/README.md), written when each edge carried the B-spline of its
// whole circle: the long arc ends where that curve closes (both ends one point of the sphere), OpenCASCADE's reader
// placed the edge's range on the curve by projecting the vertices, took the wrong end, dropped the pcurve and
// rebuilt it (2.7e-4 off). With each edge's own piece of the curve (edge_pcurve), every pcurve comes back.
TEST(StepRoundTrip, SphereArcsKeepTheirPcurvesWhenEachEdgeHasItsOwnPiece) {
  const TopoDS_Shape stored = brep_from_text(read_data("main_job_sphere_face_pcurve_rebuilt.brep"), "face");
  auto strayed_after_step = [&](const TopoDS_Shape& face, const std::string& name) {
    const std::string path = temp_path(name + ".step");
    write_step_assembly(path, {{"Face", face}});
    const std::vector<StepPart> back = read_step_parts(path);
    std::remove(path.c_str());
    double worst = 0.0;
    const int strayed = strayed_sphere_pcurves(back.at(0).shape, 1e-6, &worst);
    std::printf("[ report ] sphere face, %s: %d pcurves rebuilt, worst %.1e\n", name.c_str(), strayed, worst);
    return strayed;
  };
  EXPECT_GE(strayed_after_step(stored, "whole-circle pcurves"), 1) << "the stored face should show the reader's rebuild";
  const TopoDS_Face face = TopoDS::Face(TopExp_Explorer(stored, TopAbs_FACE).Current());
  BRep_Builder builder;
  int pieces = 0;
  for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
    if (BRep_Tool::IsClosed(edge, face)) continue;  // the seam: lines
    double t0 = 0, t1 = 0;
    const auto curve = Handle(Geom2d_BSplineCurve)::DownCast(BRep_Tool::CurveOnSurface(edge, face, t0, t1));
    if (curve.IsNull()) continue;
    const Handle(Geom2d_BSplineCurve) piece = edge_pcurve(curve, t0, t1);
    pieces += piece != curve;
    builder.UpdateEdge(edge, piece, face, BRep_Tool::Tolerance(edge));
    builder.Range(edge, face, t0, t1);
  }
  EXPECT_GT(pieces, 10);
  EXPECT_EQ(strayed_after_step(face, "own pieces"), 0);
}

TEST(StepRoundTrip, BrepTextComesBackIdentical) {
  const TopoDS_Shape part = main_job_block();
  const TopoDS_Shape back = brep_from_text(brep_to_text(part), "text");
  expect_same_solids(part, back, "main job block through BREP text");
}

TEST(StepRoundTrip, SkinnedAssemblyInATiltedCylinderComesBackValid) {
  const FlatLattice f = flatten(lattice_from_json(read_data("main_job_octet.json")));
  const gp_Ax2 axis(gp_Pnt(20.0, 20.0, 4.0), gp_Dir(0.25, 0.1, 1.0));
  LatticePartRequest request;
  request.body_brep = brep_to_text(BRepPrimAPI_MakeCylinder(axis, 8.0, 20.0).Shape());
  request.trim.skin = 0.8;
  const std::string path = temp_path("assembly.step");
  write_lattice_step(path, f, request, StepNames{});
  const std::vector<StepPart> back = read_step_parts(path);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].name, "Lattice");
  EXPECT_EQ(back[1].name, "Skin");
  // What was written: the same trim made again (it is deterministic).
  LatticePartRequest separate = request;
  separate.trim.unite_skin = false;
  const TrimResult written = trim_lattice(f, brep_from_text(*request.body_brep, "body"), separate.trim);
  expect_same_solids(written.lattice, back[0].shape, "tilted cylinder's lattice through STEP");
  expect_same_solids(written.skin, back[1].shape, "tilted cylinder's skin through STEP");
  std::remove(path.c_str());
}


// StepLayout::OneSolid: one part, the lattice united with its skin, as lattice_part_brep builds it.
TEST(StepRoundTrip, AOneSolidPartIsTheLatticeUnitedWithItsSkin) {
  std::mt19937_64 rng(3);
  const FlatLattice f = flatten(test::bcc_lattice(rng, {4, 4, 4}));
  LatticePartRequest request;
  request.body_brep = brep_to_text(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(1.5, 1.5, 0.2), gp_Dir(0.1, 0, 1)), 1.4,
                                                            2.6).Shape());
  request.trim.skin = 0.2;
  StepNames names;
  names.layout = StepLayout::OneSolid;
  names.lattice = "Part";
  const std::string path = temp_path("one_solid.step");
  TrimStats stats;
  write_lattice_step(path, f, request, names, no_progress(), &stats);
  EXPECT_GT(stats.crossing_hubs, 0);
  const std::vector<StepPart> back = read_step_parts(path);
  std::remove(path.c_str());
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].name, "Part");
  const TopoDS_Shape united = brep_from_text(lattice_part_brep(f, request), "part");
  expect_same_solids(united, back[0].shape, "one-solid part through STEP");
  EXPECT_EQ(solids_of(back[0].shape).size(), 1u);
}


// The same part gives the same bytes whenever it is written: OpenCASCADE put the time of writing in the header.
TEST(StepRoundTrip, TheSamePartWrittenTwiceGivesTheSameBytes) {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(1.0, 2.0, 3.0).Shape();
  const std::string a = temp_path("first.step"), b = temp_path("second.step");
  write_step_assembly(a, {{"Box", box}});
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // the header's time stamp counts seconds
  write_step_assembly(b, {{"Box", box}});
  const std::string first = test::file_bytes(a), second = test::file_bytes(b);
  EXPECT_FALSE(first.empty());
  EXPECT_EQ(first, second) << "the STEP header differs between two writes";
  std::remove(a.c_str());
  std::remove(b.c_str());
}

// Reals are written to 1e-9 of the unit where OpenCASCADE writes 1e-12 (issue 14: compact files): no number of
// the file has more than nine decimals in fixed notation, and a box placed at awkward coordinates comes back
// within that: its corners to 1e-9, its volume to 2e-8 relative (each edge, 0.12 long at least, moves by up to
// 1e-9).
TEST(StepRoundTrip, RealsAreWrittenToNineDecimals) {
  const gp_Pnt corner(1.0 / 3.0, -2.0 / 7.0, 123.456789012345);
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(corner, 0.1234567890123, 2.0 / 3.0, 5.0 / 7.0).Shape();
  const std::string path = temp_path("nine_decimals.step");
  write_step_assembly(path, {{"Box", box}});
  const std::string text = test::file_bytes(path);
  int fixed = 0, longest = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '.' || i == 0 || !std::isdigit(static_cast<unsigned char>(text[i - 1]))) continue;
    int decimals = 0;
    while (i + 1 + decimals < text.size() && std::isdigit(static_cast<unsigned char>(text[i + 1 + decimals])))
      ++decimals;
    if (i + 1 + decimals < text.size() && text[i + 1 + decimals] == 'E') continue;  // exponent form: 13 digits
    ++fixed;
    longest = std::max(longest, decimals);
  }
  EXPECT_GT(fixed, 20);
  EXPECT_LE(longest, 9);
  const std::vector<StepPart> back = read_step_parts(path);
  ASSERT_EQ(back.size(), 1u);
  GProp_GProps written, read;
  BRepGProp::VolumeProperties(box, written);
  BRepGProp::VolumeProperties(back[0].shape, read);
  EXPECT_NEAR(read.Mass(), written.Mass(), 2e-8 * written.Mass());
  double worst = 0.0;
  for (TopExp_Explorer v(back[0].shape, TopAbs_VERTEX); v.More(); v.Next()) {
    double nearest = 1e9;
    for (TopExp_Explorer w(box, TopAbs_VERTEX); w.More(); w.Next())
      nearest = std::min(nearest, BRep_Tool::Pnt(TopoDS::Vertex(v.Current())).Distance(
                                      BRep_Tool::Pnt(TopoDS::Vertex(w.Current()))));
    worst = std::max(worst, nearest);
  }
  EXPECT_LT(worst, 1e-9);
  std::remove(path.c_str());
}

TEST(StepRoundTrip, BadPathsAndNamesAreRefusedAndLeaveNoFile) {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(1.0, 1.0, 1.0).Shape();
  auto field_of = [&](const std::string& path, const std::string& name) -> std::string {
    try {
      write_step_assembly(path, {{name, box}});
    } catch (const InvalidInput& e) {
      const std::string message = e.what();
      return message.substr(0, message.find(':'));  // messages start with the field they name
    }
    return "";
  };
  const std::string dir = temp_path("bad");
  std::filesystem::create_directories(dir);
  EXPECT_EQ(field_of(dir + "/x" + std::string(1, '\0') + "y.step", "Box"), "path");
  EXPECT_FALSE(std::filesystem::exists(dir + "/x"));
  EXPECT_EQ(field_of(dir + "/no/such/folder/a.step", "Box"), "path");
  EXPECT_FALSE(std::filesystem::exists(dir + "/no/such/folder/a.step.partial"));
  EXPECT_EQ(field_of(dir + "/long.step", std::string(100000, 'x')), "parts");
  EXPECT_EQ(field_of(dir + "/empty.step", ""), "parts");
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  // The longest name allowed comes back whole.
  const std::string longest(kMaxStepNameLength, 'n');
  write_step_assembly(dir + "/longest.step", {{longest, box}});
  EXPECT_EQ(read_step_parts(dir + "/longest.step").at(0).name, longest);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace steady
