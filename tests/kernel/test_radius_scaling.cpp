// Density targeting: the precomputed volume model against lattice_properties of the scaled lattice, the root
// finder reaching its target, the envelope of translational lattices, bad input.
#include <gtest/gtest.h>

#include <random>

#include "lattice_test_shapes.hpp"
#include "steady/core/errors.hpp"
#include "steady/properties/lattice_properties.hpp"
#include "steady/properties/radius_scaling.hpp"
#include "brick_definition.hpp"

namespace steady {
namespace {

LatticePropertiesOptions sums_only() {
  LatticePropertiesOptions o;
  o.check_clean = false;
  return o;
}

TEST(RadiusScaling, VolumeModelMatchesPropertiesOfTheScaledLattice) {
  std::mt19937_64 rng(31);
  const test::StepKind kinds[3] = {test::StepKind::General, test::StepKind::TranslationsVW, test::StepKind::Translations};
  int compared = 0;
  for (int trial = 0; trial < 12; ++trial) {
    test::LatticeOptions o;
    o.steps = kinds[trial % 3];
    o.nodes = 1 + trial % 2;
    o.patterns = 3 + trial % 4;
    o.hull_model = trial % 4 == 3;
    o.omitted = trial % 3 == 1 ? 2 : 0;
    const Lattice lat = test::random_lattice(rng, o, Counts{3, 2 + trial % 2, 4});
    RadiusScaledVolume model(lat);
    for (double s : {0.5, 0.8, 1.0}) {
      if (s > model.max_scale()) continue;
      double expected;
      try {
        expected = lattice_properties(with_radius_scale(lat, s), sums_only()).volume;
      } catch (const InvalidInput&) {
        continue;  // this random lattice's hubs are not made of frustum stumps at this scale
      }
      EXPECT_NEAR(model(s), expected, 1e-12 * expected) << "trial " << trial << " scale " << s;
      ++compared;
    }
  }
  EXPECT_GT(compared, 20);
}

Lattice graded_bcc(std::int64_t n) {
  test::BrickDefinition d;
  d.nodes = {{Vec3(0.0), 0.2}, {Vec3(0.5, 0.5, 0.5), 0.18}};
  d.beams = {{0, 1, 0, 0, 0, 0.06, 0.06}, {0, 0, 1, 0, 0, 0.06, 0.06}, {0, 0, 0, 1, 0, 0.06, 0.06},
             {0, 0, 0, 0, 1, 0.07, 0.06}, {1, 1, 0, 0, 0, 0.06, 0.07}, {1, 1, 1, 1, 0, 0.06, 0.07}};
  d.counts = {n, n, n};
  d.u = {Similarity::translation({1, 0, 0}) * Similarity::swirl(0.002, {0, 1, 0}, {0, 0, 0}, 1.003)};
  d.v = {Similarity::translation({0, 1, 0})};
  d.w = {Similarity::translation({0, 0, 1})};
  return Lattice(d);
}

TEST(RadiusScaling, ReachesTheTargetVolume) {
  const Lattice lat = graded_bcc(6);
  const double v1 = lattice_properties(lat).volume;
  for (double factor : {0.3, 0.8, 1.0, 1.3}) {
    const RadiusScaleSolution sol = radius_scale_for_volume(lat, factor * v1);
    EXPECT_TRUE(sol.clean_verified);
    EXPECT_LE(sol.evaluations, 15);
    EXPECT_NEAR(sol.volume, factor * v1, 1e-10 * factor * v1);
    // independently: the properties of the scaled lattice
    EXPECT_NEAR(lattice_properties(with_radius_scale(lat, sol.scale)).volume, factor * v1, 1e-9 * factor * v1);
  }
}

TEST(RadiusScaling, ReachesTheTargetWhereStumpsOverlap) {
  // Hull model: every hub's caps overlap, so the search must include the quadrature corrections.
  test::BrickDefinition d;
  d.nodes = {{Vec3(0.0), 0.2}};
  d.beams = {{0, 1, 0, 0, 0}, {0, 0, 1, 0, 0}, {0, 0, 0, 1, 0}};
  d.counts = {3, 3, 2};
  d.u = {Similarity::translation({1, 0, 0}) * Similarity::swirl(0.02, {0, 0, 1}, {0, 0, 0}, 1.01)};
  d.v = {Similarity::translation({0, 1, 0})};
  d.w = {Similarity::translation({0, 0, 1})};
  const Lattice lat(d);
  ASSERT_TRUE(RadiusScaledVolume(lat).overlaps_at(1.0));
  const double target = 1.2 * lattice_properties(lat).volume;
  const RadiusScaleSolution sol = radius_scale_for_volume(lat, target);
  EXPECT_NEAR(lattice_properties(with_radius_scale(lat, sol.scale)).volume, target, 1e-9 * target);
}

TEST(RadiusScaling, DensityAndMassTargets) {
  const Lattice lat = graded_bcc(5);
  const double envelope = cell_envelope_volume(lat);
  const RadiusScaleSolution d = radius_scale_for_density(lat, 0.1, envelope);
  EXPECT_NEAR(d.volume, 0.1 * envelope, 1e-10 * envelope);
  const RadiusScaleSolution m = radius_scale_for_mass(lat, 2.0, 4.0);
  EXPECT_NEAR(m.volume, 0.5, 1e-10);
}

TEST(RadiusScaling, EnvelopeOfATranslationalLatticeIsItsCells) {
  test::BrickDefinition d;
  d.nodes = {{Vec3(0.0), 0.1}};
  d.beams = {{0, 1, 0, 0, 0}};
  d.counts = {4, 5, 6};
  d.u = {Similarity::translation({1, 0, 0})};
  d.v = {Similarity::translation({0.5, 2, 0})};
  d.w = {Similarity::translation({0, 0, 3})};
  d.placement = Similarity::dilation(2.0, {1, 1, 1});
  EXPECT_NEAR(cell_envelope_volume(Lattice(d)), 8.0 * 4 * 5 * 6 * 6.0, 1e-9);
  d.w = {Similarity::identity()};
  d.counts.w = 1;
  EXPECT_THROW(cell_envelope_volume(Lattice(d)), InvalidInput);
}

TEST(RadiusScaling, RefusesUnreachableTargets) {
  const Lattice lat = graded_bcc(4);
  EXPECT_THROW(radius_scale_for_volume(lat, -1.0), InvalidInput);
  EXPECT_THROW(radius_scale_for_volume(lat, std::nan("")), InvalidInput);
  EXPECT_THROW(radius_scale_for_density(lat, 1.5, 10.0), InvalidInput);
  try {
    radius_scale_for_volume(lat, 1e6);
    FAIL() << "an unreachable volume was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("target_volume"), std::string::npos);
  }
  EXPECT_THROW(with_radius_scale(lat, 0.0), InvalidInput);
}

}  // namespace
}  // namespace steady
