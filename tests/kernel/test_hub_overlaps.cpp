// The clean check against the brute force over all pairs of hubs and pieces, the slab window against the
// all-hubs check, touching pieces (not overlaps), and properties refusing a non-clean lattice.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "test_support.hpp"
#include "lattice_test_shapes.hpp"
#include "steady/query/hub_overlaps.hpp"
#include "steady/lattice/lattice_io.hpp"
#include "hub_test_shapes.hpp"
#include "steady/core/errors.hpp"
#include "steady/lattice/hub.hpp"
#include "steady/properties/lattice_properties.hpp"
#include "brick_definition.hpp"

namespace steady {
namespace {

Lattice bent_bcc(double bend, double scale, Counts counts) {
  test::BrickDefinition d;
  d.nodes = {{Vec3(0.0), 0.2}, {Vec3(0.5, 0.5, 0.5), 0.18}};
  d.beams = {{0, 1, 0, 0, 0, 0.1, 0.1}, {0, 0, 1, 0, 0, 0.1, 0.1}, {0, 0, 0, 1, 0, 0.1, 0.1},
             {0, 0, 0, 0, 1, 0.12, 0.1}, {1, 1, 1, 1, 0, 0.1, 0.12}, {1, 1, 0, 0, 0, 0.09, 0.11}};
  d.counts = counts;
  d.u = {Similarity::swirl(bend, {0, 0, 1}, {0.5, -6, 0}, scale) * Similarity::translation({1, 0, 0})};
  d.v = {Similarity::translation({0, 1.1, 0})};
  d.w = {Similarity::rotation(0.12, {1, 0, 0}, {0, 0, -5}) * Similarity::translation({0, 0, 1})};
  return Lattice(d);
}

TEST(HubOverlaps, MatchesBruteForceOnRandomLattices) {
  std::mt19937_64 rng(99);
  int dirty = 0;
  for (int trial = 0; trial < 20; ++trial) {
    test::LatticeOptions o;
    o.steps = trial % 2 ? test::StepKind::General : test::StepKind::Translations;
    o.nodes = 1 + trial % 3;
    o.patterns = 3 + trial % 5;
    o.hull_model = trial % 4 == 1;
    o.omitted = trial % 3 == 2 ? 2 : 0;
    const Lattice lat = test::random_lattice(rng, o, Counts{3, 2 + trial % 2, 3});
    const HubOverlapReport fast = check_hub_overlaps(lat), brute = check_hub_overlaps_brute_force(lat);
    ASSERT_TRUE(fast.verified);
    EXPECT_EQ(fast.overlap_count, brute.overlap_count) << "trial " << trial;
    ASSERT_EQ(fast.overlaps.size(), brute.overlaps.size());
    for (std::size_t k = 0; k < fast.overlaps.size(); ++k) {
      EXPECT_EQ(fast.overlaps[k].a, brute.overlaps[k].a);
      EXPECT_EQ(fast.overlaps[k].b, brute.overlaps[k].b);
    }
    dirty += fast.overlap_count > 0;
  }
  EXPECT_GT(dirty, 0);  // the test sees both verdicts
  EXPECT_LT(dirty, 20);
}

TEST(HubOverlaps, AgreesWithMonteCarloPointMembership) {
  // Independent of the distance computation: points found inside two hubs (by the definition of a hub)
  // prove an overlap, which the check must report; and most reported pairs must show such points.
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int reported = 0, confirmed = 0;
  for (int trial = 0; trial < 6; ++trial) {
    test::LatticeOptions o;
    o.steps = trial % 2 ? test::StepKind::General : test::StepKind::Translations;
    o.patterns = 4 + trial % 3;
    o.hull_model = trial % 3 == 0;
    const Lattice lat = test::random_lattice(rng, o, Counts{2, 2, 2});
    const HubOverlapReport report = check_hub_overlaps(lat, 100000);
    std::vector<HubShape> hubs;
    for (std::int64_t k = 0; k < lat.ball_count(); ++k) hubs.push_back(hub_shape(hub(lat, lat.ball_id(k))));
    for (std::size_t a = 0; a < hubs.size(); ++a)
      for (std::size_t b = a + 1; b < hubs.size(); ++b) {
        const NodeId ia = lat.ball_id(a), ib = lat.ball_id(b);
        bool listed = false;
        for (const HubOverlap& ov : report.overlaps) listed = listed || (ov.a == ia && ov.b == ib) || (ov.a == ib && ov.b == ia);
        const double ra = test::hub_reach(hubs[a]), rb = test::hub_reach(hubs[b]);
        const Vec3 lo = glm::max(hubs[a].center - ra, hubs[b].center - rb), hi = glm::min(hubs[a].center + ra, hubs[b].center + rb);
        if (lo.x >= hi.x || lo.y >= hi.y || lo.z >= hi.z) {
          EXPECT_FALSE(listed);
          continue;
        }
        bool common = false;
        for (int k = 0; k < 20000 && !common; ++k) {
          const Vec3 p = lo + (hi - lo) * Vec3(u01(rng), u01(rng), u01(rng));
          common = test::inside_hub(hubs[a], p - hubs[a].center) && test::inside_hub(hubs[b], p - hubs[b].center);
        }
        if (common) EXPECT_TRUE(listed) << "trial " << trial << ": hubs " << to_string(ia) << " and " << to_string(ib);
        reported += listed;
        confirmed += listed && common;
      }
  }
  EXPECT_GT(reported, 5);
  EXPECT_GE(confirmed, reported * 8 / 10);
}

TEST(HubOverlaps, SlabWindowCountsLikeTheAllHubsCheck) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 12; ++trial) {
    test::LatticeOptions o;
    o.steps = trial % 2 ? test::StepKind::General : test::StepKind::TranslationsVW;
    o.nodes = 1 + trial % 2;
    o.patterns = 3 + trial % 4;
    o.max_offset = trial % 3 == 2 ? 2 : 1;
    const Lattice lat = test::random_lattice(rng, o, Counts{3, 2, 7 + trial % 3});
    const HubOverlapReport all = check_hub_overlaps(lat, 1000, no_progress(), HubOverlapCheckMethod::AllHubs);
    const HubOverlapReport window = check_hub_overlaps(lat, 1000, no_progress(), HubOverlapCheckMethod::SlabWindow);
    ASSERT_TRUE(window.verified);
    EXPECT_EQ(all.overlap_count, window.overlap_count) << "trial " << trial;
  }
  // a bent lattice that overlaps in every slab
  const Lattice dirty = bent_bcc(0.08, 1.05, Counts{3, 2, 9});
  EXPECT_EQ(check_hub_overlaps(dirty, 10, no_progress(), HubOverlapCheckMethod::SlabWindow).overlap_count,
            check_hub_overlaps(dirty, 10, no_progress(), HubOverlapCheckMethod::AllHubs).overlap_count);
}

TEST(HubOverlaps, HubsOfVeryDifferentSizesKeepTheGridSmall) {
  // A dilation of 150 a step gives hubs from 0.1 to 1e7 in one lattice. The broad phase's grid had cells of the
  // median reach, so the largest hub covered some 1e20 cells: properties() took 24 GB in 10 s and the process was
  // killed for lack of memory. The cells now grow until the hubs cover few of them; the pairs are the brute force's.
  const Lattice lat = lattice_from_json(test::file_bytes(std::string(STEADY_TEST_DATA) + "/fuzz/lattice_steep_dilation_far_pattern.json"));
  const HubOverlapReport fast = check_hub_overlaps(lat, 1000), brute = check_hub_overlaps_brute_force(lat, 1000);
  EXPECT_TRUE(fast.verified);
  EXPECT_GT(fast.overlap_count, 100);
  EXPECT_EQ(fast.overlap_count, brute.overlap_count);
  EXPECT_THROW(lattice_properties(lat, LatticePropertiesOptions{{}, true, false}), InvalidInput);  // not clean, named
}

TEST(HubOverlaps, TouchingIsNotOverlapping) {
  // Balls of radius exactly half the beam length touch at the mid-plane: clean. A hair more: not clean.
  for (double radius : {0.5, 0.5 * (1 + 1e-6)}) {
    test::BrickDefinition d;
    d.nodes = {{Vec3(0.0), radius}};
    d.beams = {{0, 1, 0, 0, 0}};
    d.counts = {3, 1, 1};
    d.u = {Similarity::translation({1, 0, 0})};
    const Lattice lat(d);
    EXPECT_EQ(check_hub_overlaps(lat).clean(), radius == 0.5) << radius;
  }
}

TEST(HubOverlaps, PropertiesReportNonCleanLatticesNamingTheHubs) {
  const Lattice dirty = bent_bcc(0.08, 1.05, Counts{2, 2, 2});
  // By default: reported, and the union of the overlapping hubs is computed (test_hub_union.cpp checks it).
  const LatticeProperties p = lattice_properties(dirty);
  EXPECT_GT(p.overlap_count, 0);
  EXPECT_NE(p.overlap_description.find("hubs (0,0,0,0) and (1,0,0,0)"), std::string::npos) << p.overlap_description;
  // Without the union: refused, naming them.
  LatticePropertiesOptions no_union;
  no_union.union_overlaps = false;
  try {
    lattice_properties(dirty, no_union);
    FAIL() << "a non-clean lattice was accepted";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("not clean"), std::string::npos) << what;
    EXPECT_NE(what.find("hubs (0,0,0,0) and (1,0,0,0)"), std::string::npos) << what;
  }
  const Lattice clean = bent_bcc(0.05, 1.03, Counts{2, 2, 2});
  EXPECT_TRUE(lattice_properties(clean).clean_verified);
}

}  // namespace
}  // namespace steady
