// Lattice properties from row and slab sums against the brute-force sum over every hub, on random
// lattices (all kinds of steps, borders, both beam models, omitted nodes), and the series against the
// paper's oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <cstdio>
#include <random>

#include "lattice_test_shapes.hpp"
#include "steady/core/errors.hpp"
#include "test_support.hpp"
#include "steady/properties/similar_copies.hpp"
#include "steady/properties/lattice_properties.hpp"
#include "steady/lattice/lattice_io.hpp"
#include "steady/properties/similar_copies.hpp"
#include "brick_definition.hpp"
#include "steady/core/constants.hpp"

namespace steady {
namespace {


// Largest relative difference of the four properties (centroid relative to the lattice's size).
double property_difference(const LatticeProperties& a, const LatticeProperties& b) {
  const double size = std::sqrt(std::max(1e-300, a.inertia[0][0] + a.inertia[1][1] + a.inertia[2][2]) / a.volume);
  double d = std::abs(a.volume - b.volume) / a.volume;
  d = std::max(d, std::abs(a.area - b.area) / a.area);
  d = std::max(d, glm::length(a.centroid - b.centroid) / size);
  d = std::max(d, test::max_abs(a.inertia - b.inertia) / test::max_abs(a.inertia));
  return d;
}

double g_worst = 0.0;

// Compares the two; returns false when the lattice is refused (a node ball crosses a beam's mid-plane),
// which both must then do.
// Random lattices are seldom clean; the two sums of hubs must agree all the same, so the check is off.
LatticePropertiesOptions sums_only() {
  LatticePropertiesOptions o;
  o.check_clean = false;
  return o;
}

bool compare(const Lattice& lat, const char* what, int trial) {
  LatticeProperties brute;
  try {
    brute = lattice_properties_brute_force(lat);
  } catch (const InvalidInput&) {
    EXPECT_THROW(lattice_properties(lat, sums_only()), InvalidInput) << what << " trial " << trial;
    return false;
  }
  const LatticeProperties fast = lattice_properties(lat, sums_only());
  const double d = property_difference(brute, fast);
  g_worst = std::max(g_worst, d);
  EXPECT_LT(d, 1e-9) << what << " trial " << trial << ": volume " << fast.volume << " vs " << brute.volume;
  return true;
}

TEST(LatticeProperties, MatchBruteForceOnRandomLattices) {
  std::mt19937_64 rng(2024);
  const test::StepKind kinds[3] = {test::StepKind::General, test::StepKind::TranslationsVW, test::StepKind::Translations};
  int compared = 0;
  for (int trial = 0; trial < 36; ++trial) {
    test::LatticeOptions o;
    o.steps = kinds[trial % 3];
    o.nodes = 1 + trial % 3;
    o.patterns = 3 + trial % 6;
    o.max_offset = trial % 5 == 4 ? 2 : 1;
    o.omitted = trial % 4 == 3 ? 3 : 0;
    const Counts counts{2 + trial % 4, 1 + (trial / 2) % 4, 2 + (trial / 3) % 5};
    compared += compare(test::random_lattice(rng, o, counts), "explicit radii", trial);
  }
  EXPECT_GE(compared, 24);
}

TEST(LatticeProperties, MatchBruteForceInTheHullModel) {
  // Caps overlap in almost every hub: the overlap corrections carry real weight here.
  std::mt19937_64 rng(77);
  const test::StepKind kinds[3] = {test::StepKind::General, test::StepKind::TranslationsVW, test::StepKind::Translations};
  for (int trial = 0; trial < 6; ++trial) {
    test::LatticeOptions o;
    o.steps = kinds[trial % 3];
    o.hull_model = true;
    o.nodes = 1 + trial % 2;
    o.patterns = 3 + trial % 3;
    o.omitted = trial % 2;
    const Lattice lat = test::random_lattice(rng, o, Counts{3, 2 + trial % 2, 3});
    EXPECT_TRUE(compare(lat, "hull model", trial));
    EXPECT_GT(lattice_properties(lat, sums_only()).overlapping_hub_shapes, 0);
  }
}

TEST(LatticeProperties, ABallMayCrossTheMidPlaneOfABeamItLeavesBeforeIt) {
  // Found by fuzz_lattice_queries: balls of radius 0.6 at spacing 1 reach past their beams' mid-planes, but beams
  // of radius 0.55 leave them at 0.24 from the centre. The hubs end at the cut disks (the caps beyond lie inside
  // the cone); the brute force summed them while the row sums refused the lattice. In closed form, a row of n
  // balls is each ball's slab between its exit planes, the n - 1 cylinders between exit planes, and the two end
  // caps beyond them.
  const double R = 0.6, r = 0.55;
  const int n = 5;
  const Lattice row = Lattice::incremental({{Vec3(0.0), R}}, {{0, 0, 1, 0, 0, r, r}}, Counts{1, n, 1},
                                           Similarity::translation({0, 0, 1}), Similarity::translation({1, 0, 0}),
                                           Similarity::translation({0, 1, 0}));
  EXPECT_TRUE(compare(row, "thick beams", 0));
  const LatticeProperties fast = lattice_properties(row, sums_only());
  const double x0 = std::sqrt(R * R - r * r);
  const double slab = kPi * (2.0 * R * R * x0 - 2.0 / 3.0 * x0 * x0 * x0);
  const double cap = kPi * (2.0 / 3.0 * R * R * R - R * R * x0 + x0 * x0 * x0 / 3.0);
  const double exact = n * slab + (n - 1) * kPi * r * r * (1.0 - 2.0 * x0) + 2.0 * cap;
  EXPECT_NEAR(fast.volume, exact, 1e-12 * exact);
}

TEST(LatticeProperties, APatternWhoseBeamsAreAllOmittedDoesNotEnterTheSums) {
  // Found by fuzz_lattice_queries' 30-minute run: two groups, the first node of group 0 omitted, and a pattern from
  // node 0 to node 0 of the previous group, so that its only beam ends at the omitted node. A dilation step puts
  // the two ends 0.05 apart with end radii 0.12 and 0.05: one end ball holds the other, a beam that cannot be. The
  // brute force over the listed beams summed the lattice, the row sums refused it ("beams[3]: one end ball of a
  // beam contains the other"), though it has no such beam.
  const Lattice lat = lattice_from_json(test::file_bytes(std::string(STEADY_TEST_DATA) + "/fuzz/lattice_pattern_whose_beams_are_all_omitted.json"));
  ASSERT_EQ(lat.pattern_count(), 5);
  std::int64_t beams_of_pattern_3 = 0;
  lat.for_each_beam([&](std::int64_t, const BeamId& id, const BeamGeometry&) { beams_of_pattern_3 += id.pattern == 3; });
  EXPECT_EQ(beams_of_pattern_3, 0);
  EXPECT_TRUE(compare(lat, "pattern whose beams are all omitted", 0));
}

TEST(LatticeProperties, TranslationalLatticesNeedOnlyBorderShapes) {
  // All steps translations: every interior hub and beam is a copy; the work must not grow with the counts.
  for (bool hull : {false, true}) {
    test::LatticeOptions o;
    o.steps = test::StepKind::Translations;
    o.patterns = 6;
    o.hull_model = hull;
    std::mt19937_64 rng(5), rng2(5);
    const Lattice small = test::random_lattice(rng, o, Counts{7, 7, 7});
    const Lattice large = test::random_lattice(rng2, o, Counts{700, 700, 700});
    EXPECT_TRUE(compare(small, "translational", 0));
    const LatticeProperties a = lattice_properties(small, sums_only()), b = lattice_properties(large, sums_only());
    EXPECT_EQ(a.beam_shapes, b.beam_shapes);
    EXPECT_EQ(a.hub_shapes, b.hub_shapes);
    EXPECT_GT(b.volume, 1e6 * a.volume);
  }
}

TEST(LatticeProperties, CylindricalBendsAreSteadyAlongTheAxis) {
  // W turns the slabs about an axis along V's translation: V and W commute (their generators' Lie bracket
  // is exactly zero), so every beam row is a similar copy along j: O(u) shapes, and the same properties.
  test::BrickDefinition d;
  d.nodes = {{Vec3(0.0), 0.15}, {Vec3(0.5, 0.5, 0.5), 0.12}};
  d.beams = {{0, 1, 0, 0, 0, 0.06, 0.06}, {0, 0, 1, 0, 0, 0.06, 0.06}, {0, 0, 0, 1, 0, 0.06, 0.06},
             {0, 0, 0, 0, 1, 0.06, 0.05}, {1, 1, 1, 1, 0, 0.05, 0.06}};
  d.counts = {4, 5, 4};
  d.u = {Similarity::translation({1, 0, 0})};
  d.v = {Similarity::translation({0, 1, 0})};
  d.w = {Similarity::rotation(-0.05, {0, 1, 0}, {-20, 0, 0})};
  const Lattice lat(d);
  EXPECT_TRUE(exactly_commute(d.v.similarity, d.w.similarity));
  EXPECT_FALSE(exactly_commute(d.u.similarity, d.w.similarity));
  EXPECT_FALSE(exactly_commute(Similarity::dilation(1.1, {0, 0, 0}), d.v.similarity));
  const LatticeProperties fast = lattice_properties(lat);
  EXPECT_LE(fast.beam_shapes, 4 * 5 + 2 * 5);  // per pattern at most one row of u shapes (plus omissions: none)
  EXPECT_LT(property_difference(lattice_properties_brute_force(lat), fast), 1e-12);
}

TEST(LatticeProperties, SeriesReproduceThePaperOracle) {
  // steady-lattices digest 11.2: slab 0 is one ball of volume 2 at G0 = (3, 1, 2), K = 12 copies by W.
  const double v0 = 2.0, r0 = std::cbrt(3.0 * v0 / (4.0 * kPi));
  const Vec3 G0(3, 1, 2), F(1, -2, 0.5), N = glm::normalize(Vec3(0.2, 0.3, 1.0));
  MassMoments ball = ball_moments(r0);
  SimilarityTransform to_g0;
  to_g0.translation = G0;
  ball = transformed(ball, to_g0);
  auto spherical_inertia = [](const MassMoments& m) {
    const Mat3 s = central_second_moment(m);
    return s[0][0] + s[1][1] + s[2][2];
  };
  const MassMoments swirl = sum_of_copies(Similarity::swirl(0.25, N, F, 1.07), Vec3(0.0), ball, 12);
  EXPECT_NEAR(swirl.volume, 92.63955944898, 1e-9);
  EXPECT_NEAR(glm::length(centroid(swirl) - Vec3(-2.0191481671559, -0.5021803516376, 5.4642173547311)), 0.0, 1e-11);
  EXPECT_NEAR(spherical_inertia(swirl), 1083.11702738327, 1e-8);
  const MassMoments screw = sum_of_copies(Similarity::screw(0.25, N, F, 0.4), Vec3(0.0), ball, 12);
  EXPECT_NEAR(glm::length(centroid(screw) - Vec3(0.5358110857811, 0.7028307716314, 4.9206206301560)), 0.0, 1e-11);
  EXPECT_NEAR(spherical_inertia(screw), 165.36546518057, 1e-9);
  // and the papers' hand checks: v0 = 1, m = 2, K = 3 gives 73 (volume) and 21 (area)
  EXPECT_DOUBLE_EQ(geometric_sum(3 * std::log(2.0), 3), 73.0);
  EXPECT_DOUBLE_EQ(geometric_sum(2 * std::log(2.0), 3), 21.0);
}

TEST(LatticeProperties, DoublingIsStableWhereTheFixedPointRunsAway) {
  // A swirl with scale 1 + 1e-12: its fixed point is ~1e12 away and the papers' closed form cancels
  // catastrophically; the doubling sum must agree with the plain sum of copies to rounding.
  MassMoments ball = ball_moments(0.3);
  const Similarity W = Similarity::swirl(0.1, Vec3(0, 0, 1), Vec3(0.0), 1.0 + 1e-12) * Similarity::translation({0, 0, 1});
  MassMoments plain;
  for (int k = 0; k < 1000; ++k) plain += transformed(ball, W.power(k).transform());
  const MassMoments fast = sum_of_copies(W, Vec3(0.0), ball, 1000);
  EXPECT_NEAR(fast.volume, plain.volume, 1e-13 * plain.volume);
  EXPECT_LT(glm::length(centroid(fast) - centroid(plain)), 1e-10);
  EXPECT_LT(test::max_abs(central_inertia(fast) - central_inertia(plain)), 1e-9 * test::max_abs(central_inertia(plain)));
}

TEST(LatticeProperties, ReportsTheLargestDifference) {
  std::printf("[ report ] lattice properties vs brute force: largest relative difference %.3e\n", g_worst);
}

}  // namespace
}  // namespace steady
