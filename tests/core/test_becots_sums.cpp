// Closed-form volume, area and centroid of BeCOTS patterns of balls against the brute-force sums over every copy.
#include <gtest/gtest.h>

#include <optional>
#include <random>

#include "cots_test_support.hpp"
#include "steady/core/errors.hpp"
#include "steady/cots/becots_sums.hpp"

namespace {

using steady::Ball;
using steady::BecotsMap;
using steady::InvalidInput;
using steady::PatternProperties;
using steady::Vec3;
using cots_test::kPi;

PatternProperties brute_force(const BecotsMap& map, const std::vector<Ball>& balls, int nu, int nv, double du, double dv) {
  PatternProperties p;
  Vec3 moment(0.0);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const auto s = map.field(i * du, j * dv);
      for (const Ball& b : balls) {
        const Ball c = s.apply(b);
        const double v = 4.0 / 3.0 * kPi * c.radius * c.radius * c.radius;
        p.volume += v;
        p.area += 4.0 * kPi * c.radius * c.radius;
        moment += v * c.center;
      }
    }
  p.centroid = moment / p.volume;
  return p;
}

TEST(BecotsSums, ClosedFormsMatchTheSumsOverEveryCopy) {
  std::mt19937_64 rng(37);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), param(0.0, 1.0);
  double worst_volume = 0.0, worst_area = 0.0, worst_centroid = 0.0;
  int patterns = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::optional<BecotsMap> map;
    try {
      if (trial % 4 == 0)
        map = BecotsMap({unit(rng), unit(rng), unit(rng)}, {unit(rng), unit(rng), unit(rng)},
                        {unit(rng), unit(rng), unit(rng)}, {unit(rng), unit(rng), unit(rng)});
      else if (trial % 4 == 1)
        map = BecotsMap({unit(rng), unit(rng), 0}, {unit(rng), unit(rng), 0}, {unit(rng), unit(rng), 0},
                        {unit(rng), unit(rng), 0});
      else if (trial % 4 == 2)  // |AB| = |CD|: U a pure rotation, its scale series is a plain count
        map = BecotsMap::from_field({unit(rng), unit(rng), unit(rng)}, {unit(rng), unit(rng), unit(rng)},
                                    {2 + unit(rng), unit(rng), unit(rng)}, {0.0, 3 * unit(rng)}, {0.3 * unit(rng), 3 * unit(rng)});
      else
        map = BecotsMap::from_field({unit(rng), unit(rng), unit(rng)}, {unit(rng), unit(rng), unit(rng)},
                                    {2 + unit(rng), unit(rng), unit(rng)}, {0.4 * unit(rng), 8 * unit(rng)},
                                    {0.4 * unit(rng), 8 * unit(rng)});
    } catch (const InvalidInput&) {
      continue;
    }
    const int nu = 1 + static_cast<int>(rng() % 40), nv = 1 + static_cast<int>(rng() % 40);
    const double du = 1.0 / std::max(1, nu - 1), dv = 1.0 / nv;
    std::vector<Ball> balls;
    for (int n = 0; n < 1 + trial % 3; ++n)
      balls.push_back({map->map(param(rng) * du, param(rng) * dv) + 0.05 * Vec3(unit(rng), unit(rng), unit(rng)),
                       0.01 + 0.05 * param(rng)});
    const PatternProperties closed = steady::becots_ball_pattern_properties(*map, balls, nu, nv, du, dv);
    const PatternProperties brute = brute_force(*map, balls, nu, nv, du, dv);
    worst_volume = std::max(worst_volume, std::abs(closed.volume - brute.volume) / brute.volume);
    worst_area = std::max(worst_area, std::abs(closed.area - brute.area) / brute.area);
    worst_centroid = std::max(worst_centroid, glm::length(closed.centroid - brute.centroid) /
                                                  std::max(1.0, glm::length(brute.centroid)));
    ++patterns;
  }
  EXPECT_GT(patterns, 250);
  EXPECT_LT(worst_volume, 1e-12);
  EXPECT_LT(worst_area, 1e-12);
  EXPECT_LT(worst_centroid, 1e-10);
  std::printf("[ measured ] BeCOTS pattern sums, %d patterns: volume %.2g, area %.2g, centroid %.2g (relative)\n",
              patterns, worst_volume, worst_area, worst_centroid);
}

TEST(BecotsSums, ParallelogramsAndBadInput) {
  // A flat parallelogram: translations, the counts and the mean shift.
  const BecotsMap map({0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0});
  const std::vector<Ball> balls{{{0.1, 0.2, 0.0}, 0.05}};
  const PatternProperties closed = steady::becots_ball_pattern_properties(map, balls, 5, 7, 0.25, 1.0 / 6);
  const PatternProperties brute = brute_force(map, balls, 5, 7, 0.25, 1.0 / 6);
  EXPECT_NEAR(closed.volume, brute.volume, 1e-15);
  EXPECT_LT(glm::length(closed.centroid - brute.centroid), 1e-14);
  EXPECT_NEAR(steady::becots_scale_sum(map, 3.0, 5, 7, 0.25, 0.1), 35.0, 1e-13);
  EXPECT_THROW(steady::becots_ball_pattern_properties(map, balls, 0, 7, 0.25, 0.1), InvalidInput);
  EXPECT_THROW(steady::becots_ball_pattern_properties(map, {{{0, 0, 0}, -1.0}}, 2, 2, 0.25, 0.1), InvalidInput);
  EXPECT_THROW(steady::becots_scale_sum(map, 3.0, 2, 2, 0.0, 0.1), InvalidInput);
}

}  // namespace
