// Hostile or broken body inputs (BREP text, STEP files), each found by a fuzz target (tests/fuzz,
// docs/reliability.md) or an issue-16 reproducer: refused with InvalidInput naming the field, never a hang, a crash
// inside OpenCASCADE or a body that classifies points wrongly. The inputs are in data/fuzz/ (data/README.md).
#include <gtest/gtest.h>

#include <BRepPrimAPI_MakeBox.hxx>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include "test_support.hpp"
#include "brep/child_reader.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/brep/solid_body.hpp"
#include "steady/brep/step_assembly.hpp"
#include "steady/brep/body_filter.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/progress.hpp"

namespace steady {
namespace {

std::string read_data(const std::string& name) { return test::file_bytes(std::string(STEADY_TEST_DATA) + "/" + name); }

// The message of the InvalidInput `call` throws, or a failure.
template <class F>
std::string refusal(F&& call) {
  try {
    call();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted";
  return "";
}

TEST(BodyInputs, TruncatedBrepTextIsRefusedNotAHang) {
  // Issue 16, repro reliability/01 (found again by tests/fuzz/fuzz_body_brep): OpenCASCADE's reader looped forever
  // on a BREP text cut in the middle of an edge's representations. Every prefix of a box's text, cut at each line,
  // must now be refused (or, when complete, read); a watchdog turns a hang into a failure.
  const std::string text = brep_to_text(BRepPrimAPI_MakeBox(4, 4, 4).Shape());
  std::atomic<bool> done{false};
  std::thread watchdog([&] {
    for (int t = 0; t < 600 && !done; ++t) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (!done) {
      std::fprintf(stderr, "brep_from_text did not return within 60 s on a truncated text\n");
      std::abort();
    }
  });
  int refused = 0, cuts = 0;
  for (std::size_t end = text.find('\n'); end != std::string::npos; end = text.find('\n', end + 1), ++cuts) {
    try {
      EXPECT_FALSE(brep_from_text(text.substr(0, end), "body").IsNull());
    } catch (const InvalidInput& e) {
      ++refused;
      EXPECT_EQ(std::string(e.what()).rfind("body: ", 0), 0u) << e.what();
    }
  }
  EXPECT_THROW(brep_from_text(text.substr(0, text.size() / 2), "body"), InvalidInput);
  done = true;
  watchdog.join();
  EXPECT_GT(refused, cuts / 2);
  EXPECT_FALSE(brep_from_text(text, "body").IsNull());  // the whole text still reads
}

TEST(BodyInputs, BrepTextWithAFaceWithoutSurfaceIsRefused) {
  // Found by tests/fuzz/fuzz_body_brep: a box whose fourth surface record is cut short. OpenCASCADE's reader
  // leaves that face without a surface and says nothing; BRepCheck (SolidBody, brep_properties) then crashed
  // the process (SEGV in BRepCheck_Edge::InContext). Refused when read, naming the face.
  const std::string text = read_data("fuzz/brep_face_without_surface.brep");
  try {
    brep_from_text(text, "body");
    ADD_FAILURE() << "a face without a surface was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("body: face #4 has no surface"), std::string::npos) << e.what();
  }
}

TEST(BodyInputs, BrepTextWithAnEdgeWithoutCurveIsRefused) {
  // Found by fuzz_body_brep: two curve records merged into one line, so the twelfth curve did not read and the
  // reader dropped the 3D curve of the edge using it; BRepCheck_Edge::InContext then crashed.
  const std::string message = refusal([] { brep_from_text(read_data("fuzz/brep_edge_without_curve.brep"), "body"); });
  EXPECT_NE(message.find("body: edge #"), std::string::npos) << message;
  EXPECT_NE(message.find("no 3D curve"), std::string::npos) << message;
}

TEST(BodyInputs, BrepTextWithAnEllipseOfNoSizeIsRefusedNotAHang) {
  // Found by fuzz_body_brep once bodies were read in a reader process: one digit of a box's text turned a line
  // pcurve ("1 0 4 1 0") into an ellipse ("3 ..."), which took the next numbers as its axes and radii: radii 0. The
  // text reads; OpenCASCADE's checker (BRepCheck_Wire::SelfIntersect, line against ellipse) then ran for ever (more
  // than 146 s under ASan, in the reader process). Refused when read, naming the edge.
  const std::string text = read_data("fuzz/brep_ellipse_pcurve_of_no_size.brep");
  for (const std::string& message : {refusal([&] { brep_from_text(text, "body"); }),
                                     refusal([&] { read_body_brep(text, "body"); })}) {
    EXPECT_EQ(message.rfind("body: edge #", 0), 0u) << message;
    EXPECT_NE(message.find("a curve on surface (pcurve) that is a circle or conic of no size"), std::string::npos)
        << message;
  }
}

TEST(BodyInputs, BodyWithAHugeToleranceIsRefused) {
  // Found by fuzz_body_brep: a vertex tolerance of 1 (a digit of "1e-07" changed) on a box of 4 is valid for
  // BRepCheck, and points 0.7 outside the box's corner were classified inside.
  const TopoDS_Shape shape = brep_from_text(read_data("fuzz/brep_vertex_tolerance_1.brep"), "body");
  const std::string message = refusal([&] { SolidBody body(shape, "body"); });
  EXPECT_NE(message.find("body: has a tolerance of 1,"), std::string::npos) << message;
  // The same box with its tolerances as written is a body, and the point is outside it.
  const SolidBody box(brep_from_text(read_data("../../fuzz/corpus/fuzz_body_brep/box.brep"), "body"), "body");
  EXPECT_FALSE(box.contains({4.3, 4.3, 4.3}));
}

TEST(BodyInputs, StepWithAnUnresolvedReferenceIsRefused) {
  // Found by fuzz_body_step: a cut-short PRODUCT_DEFINITION record leaves entities whose references did not load;
  // OpenCASCADE's translator dereferenced a face's missing geometry (SEGV in StepToTopoDS_TranslateFace::Init).
  const std::string path = std::string(STEADY_TEST_DATA) + "/fuzz/step_unresolved_face_geometry.step";
  const std::string message = refusal([&] { read_step_parts(path); });
  EXPECT_EQ(message.rfind("path: ", 0), 0u) << message;
  // A file the kernel wrote still reads.
  EXPECT_EQ(read_step_parts(std::string(STEADY_TEST_DATA) + "/../../fuzz/corpus/fuzz_body_step/one_ball.step").size(), 1u);
}

TEST(BodyInputs, StepBodyThatClassifiesFarPointsInsideIsRefused) {
  // Found by the 30-minute fuzz_body_step run: two balls and a beam with one ORIENTED_EDGE naming the wrong edge (and
  // a few numbers changed) read as one "valid" solid of half the volume, which classified a point outside its
  // bounding box as inside. SolidBody (every trimming's body) refuses it.
  const std::vector<StepPart> parts = read_step_parts(std::string(STEADY_TEST_DATA) + "/fuzz/step_edge_reference_changed.step");
  ASSERT_EQ(parts.size(), 1u);
  const std::string message = refusal([&] { SolidBody body(parts[0].shape, "body"); });
  EXPECT_EQ(message.rfind("body: is not a consistent solid: OpenCASCADE classifies a point inside that its faces put outside its bounding box", 0), 0u)
      << message;
  // The file it came from is a body.
  const std::vector<StepPart> good =
      read_step_parts(std::string(STEADY_TEST_DATA) + "/../../fuzz/corpus/fuzz_body_step/two_balls_one_beam.step");
  ASSERT_EQ(good.size(), 1u);
  EXPECT_GT(SolidBody(good[0].shape, "body").volume(), 0.25);
}

// Issue 16: inputs on which OpenCASCADE's own readers crash (SIGSEGV) before the kernel gets control, found by the
// fuzz targets (tests/fuzz/findings). They are read in a reader process of their own (brep/child_reader.hpp): the
// crash ends that process, and the caller gets InvalidInput naming the field.
std::string finding(const std::string& name) { return std::string(STEADY_TEST_DATA) + "/../../fuzz/findings/" + name; }

TEST(BodyInputs, BrepTextThatCrashesTheReaderIsRefusedNotACrash) {
  // SEGV in Geom2d_OffsetCurve::SetBasisCurve: a 2D offset curve whose basis curve does not read.
  const std::string text = read_data("../../fuzz/findings/brep_offset_curve_without_basis.brep");
  for (const std::string& message : {refusal([&] { read_body_brep(text, "body"); }),
                                     refusal([&] { inside_brep(text, "body"); })}) {
    EXPECT_EQ(message.rfind("body: the BREP text crashed OpenCASCADE's BREP reader (", 0), 0u) << message;
    EXPECT_NE(message.find("it is corrupt"), std::string::npos) << message;
  }
}

TEST(BodyInputs, StepThatCrashesTheReaderIsRefusedNotACrash) {
  // SEGV in StepShape_EdgeLoop::EdgeListValue, inside OpenCASCADE's own semantic check in ReadFile.
  const std::string path = finding("step_edge_loop_check.step");
  const std::string message = refusal([&] { read_step_parts(path); });
  EXPECT_EQ(message.rfind("path: '" + path + "' crashed OpenCASCADE's STEP reader (", 0), 0u) << message;
}

// BREP text with every shape's "checked" flag cleared (the third of its seven flags): BinTools does not carry it,
// and it is only a mark that BRepCheck has looked at the shape.
std::string without_checked_flags(std::string text) {
  std::istringstream in(text);
  std::string line, out;
  while (std::getline(in, line)) {
    if (line.size() == 7 && line.find_first_not_of("01") == std::string::npos) line[2] = '0';
    out += line + "\n";
  }
  return out;
}

TEST(BodyInputs, TheReaderProcessGivesBackTheShapeItRead) {
  // What comes back from the reader process (BinTools binary) is the shape as read in this process, every number
  // and every sub-shape.
  const std::string text = read_data("../../fuzz/corpus/fuzz_body_brep/cylinder.brep");
  EXPECT_EQ(without_checked_flags(brep_to_text(read_body_brep(text, "body"))),
            without_checked_flags(brep_to_text(brep_from_text(text, "body"))));
  // A STEP file the kernel wrote: its part's volume, name and colour as written.
  const std::string path = testing::TempDir() + "/reader_process_box_" + std::to_string(getpid()) + ".step";
  write_step_assembly(path, {{"Box", BRepPrimAPI_MakeBox(4, 5, 6).Shape(), {0.25, 0.5, 0.75}, true}});
  const std::vector<StepPart> parts = read_step_parts(path);
  std::remove(path.c_str());
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].name, "Box");
  EXPECT_TRUE(parts[0].has_color);
  EXPECT_NEAR(parts[0].color[1], 0.5, 1e-6);
  EXPECT_NEAR(shape_volume(parts[0].shape), 120.0, 1e-9);
  // A refusal made in the reader process comes back with its message.
  EXPECT_NE(refusal([] { read_body_brep("not a shape", "body"); }).find("body: "), std::string::npos);
  EXPECT_EQ(refusal([&] { inside_brep(brep_to_text(BRepPrimAPI_MakeBox(1, 1, 1).TopFace()), "body"); }),
            "body: is not a solid (the shape holds no solid)");
}

// BREP text that OpenCASCADE's reader takes many seconds over: millions of line records, and no shape after them.
std::string slow_brep_text(int curves) {
  std::string text = "\nCASCADE Topology V1, (c) Matra-Datavision\nLocations 0\nCurve2ds 0\nCurves " +
                     std::to_string(curves) + "\n";
  for (int i = 0; i < curves; ++i) text += "1 0 0 0 1 0 0 \n";
  return text;
}

TEST(BodyInputs, ACancelStopsTheReaderProcessWithinASecond) {
  const std::string text = slow_brep_text(3000000);  // about 3 s to read here
  const auto start = std::chrono::steady_clock::now();
  const auto cancel_at = start + std::chrono::milliseconds(300);
  Progress progress([&](double) { return std::chrono::steady_clock::now() < cancel_at; });
  progress.set_report_interval(std::chrono::milliseconds(0));
  const ProgressScope scope(&progress);
  EXPECT_THROW(read_body_brep(text, "body"), Cancelled);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 1.3);  // 0.3 s before the cancel, then a poll of 50 ms and the kill
}

TEST(BodyInputs, AReaderStillRunningAfterItsTimeLimitIsStopped) {
  // What a headless script with nobody to press Ctrl-C gets when a reader loops on a corrupt file: a refusal once
  // the limit (here 0.5 s, set as a user would) has passed, naming the field and how to allow more time.
  const std::string text = slow_brep_text(3000000);  // about 3 s to read here
  ASSERT_EQ(::setenv("STEADY_READER_SECONDS", "0.5", 1), 0);
  const auto start = std::chrono::steady_clock::now();
  const std::string message = refusal([&] { read_body_brep(text, "body"); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ::unsetenv("STEADY_READER_SECONDS");
  EXPECT_LT(seconds, 1.5);  // the limit, then a poll of 50 ms and the kill
  EXPECT_NE(message.find("body: OpenCASCADE's BREP reader was still reading the BREP text after 0.5 s"), std::string::npos)
      << message;
  EXPECT_NE(message.find("STEADY_READER_SECONDS"), std::string::npos);
  // Unset (or not a positive number), the limit grows with the input: 120 s, plus 30 s per MB.
  ASSERT_EQ(::setenv("STEADY_READER_SECONDS", "-3", 1), 0);
  EXPECT_DOUBLE_EQ(reader_time_limit_seconds(2000000), 180.0);
  ::unsetenv("STEADY_READER_SECONDS");
  EXPECT_DOUBLE_EQ(reader_time_limit_seconds(0), 120.0);
}

}  // namespace
}  // namespace steady
