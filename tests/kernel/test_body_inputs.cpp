// Hostile or broken body inputs (BREP text, STEP files), each found by a fuzz target (tests/fuzz,
// docs/reliability.md) or an issue-16 reproducer: refused with InvalidInput naming the field, never a hang, a crash
// inside OpenCASCADE or a body that classifies points wrongly. The inputs are in data/fuzz/ (data/README.md).
#include <gtest/gtest.h>

#include <BRepPrimAPI_MakeBox.hxx>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "steady/brep/brep_io.hpp"
#include "steady/brep/solid_body.hpp"
#include "steady/brep/step_assembly.hpp"
#include "steady/core/errors.hpp"

namespace steady {
namespace {

std::string read_data(const std::string& name) {
  std::ifstream in(std::string(STEADY_TEST_DATA) + "/" + name, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

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

}  // namespace
}  // namespace steady
