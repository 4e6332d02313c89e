// The up-front size estimate of ball queries (LatticeQuery::surely_hit): a lower bound of the result, so that the
// memory check built on it never refuses a query that would fit, and tight for balls holding the lattice.
#include <gtest/gtest.h>

#include <random>

#include "sample_lattices.hpp"
#include "steady/query/lattice_query.hpp"

namespace steady {
namespace {
using namespace test;

std::int64_t result_size(const LatticeQuery& q, const Ball& query) {
  const BallQueryResult r = q.query_ball(query);
  return static_cast<std::int64_t>(r.balls.size() + r.beams.size());
}

void expect_lower_bound_on(const Lattice& lat, std::mt19937_64& rng, int queries, std::int64_t* largest_bound) {
  const LatticeQuery q(lat);
  const Ball& bound = q.bound();
  std::uniform_real_distribution<double> unit(-1.0, 1.0), fraction(0.0, 1.2);
  for (int t = 0; t < queries; ++t) {
    const Vec3 center = bound.center + 0.7 * bound.radius * Vec3(unit(rng), unit(rng), unit(rng));
    const Ball query{center, fraction(rng) * bound.radius};
    const std::int64_t sure = q.surely_hit(query);
    EXPECT_LE(sure, result_size(q, query)) << "query " << t << " radius " << query.radius;
    *largest_bound = std::max(*largest_bound, sure);
  }
  // A ball holding the whole lattice meets every element, and the estimate knows it.
  const Ball everything{bound.center, 1.01 * bound.radius};
  EXPECT_EQ(q.surely_hit(everything), lat.ball_count() + lat.beam_count());
}

TEST(ResultEstimate, IsALowerBoundOfTheResultOnSampleLattices) {
  std::mt19937_64 rng(16);
  std::int64_t largest = 0;
  expect_lower_bound_on(regular_bcc({12, 10, 8}), rng, 40, &largest);
  expect_lower_bound_on(cylindrical_bcc({6, 24, 5}), rng, 40, &largest);
  expect_lower_bound_on(bent_twisted_tapered({10, 8, 6}), rng, 40, &largest);
  // The estimate is not trivially zero: some query of these had blocks surely inside.
  EXPECT_GT(largest, 1000);
}

TEST(ResultEstimate, IsALowerBoundOnRandomLatticesWithOmissions) {
  std::mt19937_64 rng(1616);
  for (int index = 0; index < 40; ++index) {
    std::int64_t largest = 0;
    expect_lower_bound_on(random_lattice(rng, index), rng, 10, &largest);
  }
}

}  // namespace
}  // namespace steady
