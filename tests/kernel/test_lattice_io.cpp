// The lattice file format: exact round trips, hand-written similarity forms, and refusal of malformed
// or inconsistent files with a message naming the field.
#include <gtest/gtest.h>

#include <cstring>

#include "steady/core/errors.hpp"
#include "steady/lattice/lattice_io.hpp"
#include "brick_definition.hpp"

namespace steady {
namespace {

Lattice sample() {
  test::BrickDefinition d;
  d.nodes = {{{0.1, 0.2, 0.30000000000000004}, 0.2}, {{0.5, 0.5, 0.5}, 1.0 / 3.0}};
  d.beams = {{0, 1, 0, 0, 0}, {0, 0, 0, 0, 1, 0.05, 0.07}, {1, 1, 1, 1, 0}};
  d.counts = {5, 4, 3};
  d.u = {Similarity::swirl(0.7, {0.1, 0.2, 1}, {1, 2, 3}, 1.05), StepControl::Cumulative};
  d.v = {Similarity::screw(10.0, {0, 0, 1}, {1, 0, 0}, 3.0), StepControl::Cumulative};
  d.w = {Similarity::translation({0, 0, 1.1})};
  d.placement = Similarity::rotation(0.3, {1, 0, 0}, {0, 5, 0});
  d.omitted = {{1, 2, 0, 1}, {4, 3, 2, 0}};
  return Lattice(d);
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const Vec3& a, const Vec3& b) { return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z); }
bool same_bits(const Similarity& a, const Similarity& b) {
  return same_bits(a.log_scale(), b.log_scale()) && same_bits(a.rotation_vector(), b.rotation_vector()) &&
         same_bits(a.velocity(), b.velocity());
}

TEST(LatticeFile, RoundTripIsExact) {
  const Lattice a = sample();
  const std::string text = lattice_to_json(a);
  const Lattice b = lattice_from_json(text);
  EXPECT_EQ(lattice_to_json(b), text);
  const auto &da = a.definition(), &db = b.definition();
  ASSERT_EQ(da.nodes.size(), db.nodes.size());
  for (std::size_t n = 0; n < da.nodes.size(); ++n) {
    EXPECT_TRUE(same_bits(da.nodes[n].center, db.nodes[n].center));
    EXPECT_TRUE(same_bits(da.nodes[n].radius, db.nodes[n].radius));
  }
  const auto& la = dynamic_cast<const SteadyBrickLayout&>(a.layout());
  const auto& lb = dynamic_cast<const SteadyBrickLayout&>(b.layout());
  for (int axis = 0; axis < 3; ++axis) EXPECT_TRUE(same_bits(la.control(axis).similarity, lb.control(axis).similarity));
  EXPECT_TRUE(same_bits(la.placement(), lb.placement()));
  EXPECT_EQ(lb.control(0).control, StepControl::Cumulative);
  EXPECT_EQ(lb.control(2).control, StepControl::Incremental);
  ASSERT_EQ(db.beams.size(), 3u);
  EXPECT_TRUE(same_bits(*db.beams[1].from_radius, 0.05));
  EXPECT_FALSE(db.beams[0].has_radii());
  EXPECT_EQ(db.omitted.size(), 2u);
  EXPECT_EQ(a.ball_count(), b.ball_count());
  EXPECT_EQ(a.beam_count(), b.beam_count());
  // every ball is bit-identical
  for (std::int64_t q = 0; q < a.ball_count(); ++q) {
    const Ball x = a.ball(a.ball_id(q)), y = b.ball(b.ball_id(q));
    EXPECT_TRUE(same_bits(x.center, y.center) && same_bits(x.radius, y.radius));
  }
}

TEST(LatticeFile, HandWrittenSimilarityForms) {
  const std::string text = R"({
    "format": "steady-lattice", "version": 1, "units": "mm",
    "nodes": [{"center": [0, 0, 0], "radius": 0.2}],
    "beams": [{"from": 0, "offset": [1, 0, 0], "to": 0}],
    "counts": [4, 3, 2],
    "U": {"type": "swirl", "angle": 0.1, "axis": [0, 0, 1], "center": [0, -10, 0], "scale": 1.02},
    "V": {"type": "frames", "from": {"origin": [0,0,0], "x": [1,0,0], "y": [0,1,0], "z": [0,0,1]},
                            "to":   {"origin": [0,2,0], "x": [0,1,0], "y": [-1,0,0], "z": [0,0,1]}},
    "W": {"type": "translation", "vector": [0, 0, 1], "control": "cumulative"},
    "placement": {"type": "rotation", "angle": 1.0, "axis": [1, 0, 0]}
  })";
  const Lattice lat = lattice_from_json(text);  // version 1: the steady brick's fields at the top level
  const SteadyBrick& brick = *lat.layout().steady_brick();
  EXPECT_EQ(brick.step_along(0).kind(), SimilarityKind::Swirl);
  EXPECT_EQ(brick.step_along(1).kind(), SimilarityKind::Rotation);
  EXPECT_NEAR(brick.step_along(2).translation_part().z, 1.0, 1e-15);  // w = 2: one step carries the whole translation
  EXPECT_EQ(lat.beam_count(), 3 * 3 * 2);
}

std::string refusal(const std::string& text) {
  try {
    lattice_from_json(text);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "accepted";
}

// Replace the first occurrence of `from` in the sample file by `to`.
std::string edited(const std::string& from, const std::string& to) {
  std::string text = lattice_to_json(sample(), -1);
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

TEST(LatticeFile, MalformedFilesAreRefusedNamingTheField) {
  EXPECT_NE(refusal("{not json").find("not valid JSON"), std::string::npos);
  EXPECT_NE(refusal("[1,2]").find("top level"), std::string::npos);
  EXPECT_NE(refusal(edited("\"version\":2", "\"version\":3")).find("version: unsupported version 3"), std::string::npos);
  EXPECT_NE(refusal(edited("\"kind\":\"steady-brick\"", "\"kind\":\"spiral\"")).find("layout.kind: unknown layout kind"),
            std::string::npos);
  EXPECT_NE(refusal(edited("\"layout\"", "\"layuot\"")).find("layuot: unknown field"), std::string::npos);
  EXPECT_NE(refusal(edited("\"format\":\"steady-lattice\"", "\"format\":\"mesh\"")).find("format"), std::string::npos);
  EXPECT_NE(refusal(edited("\"radius\":0.2", "\"radius\":-0.2")).find("nodes[0].radius: must be > 0"), std::string::npos);
  EXPECT_NE(refusal(edited("\"radius\":0.2", "\"radius\":null")).find("nodes[0].radius: expected a number"),
            std::string::npos);
  EXPECT_NE(refusal(edited("\"radius\":0.2", "\"radius\":1e999")).find("number overflow"),
            std::string::npos);
  EXPECT_NE(refusal(edited("\"to\":0", "\"to\":7")).find("beams[0].to: node 7 does not exist"), std::string::npos);
  EXPECT_NE(refusal(edited("\"counts\":[5,4,3]", "\"counts\":[5,0,3]")).find("counts.v: must be >= 1"),
            std::string::npos);
  EXPECT_NE(refusal(edited("\"counts\":[5,4,3]", "\"counts\":[5,4]")).find("counts: expected an array of 3"),
            std::string::npos);
  EXPECT_NE(refusal(edited("\"counts\":[5,4,3],", "")).find("counts: missing field"), std::string::npos);
  EXPECT_NE(refusal(edited("\"type\":\"generator\"", "\"type\":\"shear\"")).find("unknown similarity type 'shear'"),
            std::string::npos);
  EXPECT_NE(refusal(edited("\"control\":\"cumulative\"", "\"control\":\"sometimes\"")).find("layout.U.control"),
            std::string::npos);
  EXPECT_NE(refusal(edited("\"nodes\"", "\"nodez\"")).find("nodez: unknown field"), std::string::npos);
  EXPECT_NE(refusal(edited("\"omitted\":[[1,2,0,1]", "\"omitted\":[[1,2,9,1]")).find("omitted[0]"), std::string::npos);
  const std::string bad_swirl = R"({"format": "steady-lattice", "version": 1,
    "nodes": [{"center": [0, 0, 0], "radius": 0.2}], "beams": [], "counts": [2, 1, 1],
    "U": {"type": "swirl", "angle": 0.1, "axis": [0, 0, 0], "scale": 1.02},
    "V": {"type": "identity"}, "W": {"type": "identity"}})";
  EXPECT_NE(refusal(bad_swirl).find("U: swirl.axis"), std::string::npos);
  const std::string bad_frame = R"({"format": "steady-lattice", "version": 1,
    "nodes": [{"center": [0, 0, 0], "radius": 0.2}], "beams": [], "counts": [2, 1, 1],
    "U": {"type": "frames", "from": {"origin": [0,0,0], "x": [1,0,0], "y": [0,1,0], "z": [0,0,1]},
                            "to":   {"origin": [0,2,0], "x": [1,0,0], "y": [1,1,0], "z": [0,0,1]}},
    "V": {"type": "identity"}, "W": {"type": "identity"}})";
  EXPECT_NE(refusal(bad_frame).find("U.to"), std::string::npos);
}

}  // namespace
}  // namespace steady
