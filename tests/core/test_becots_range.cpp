// The BeCOTS RangeFinder against brute force: its candidate groups must hold every group with a ball that meets the
// query (0 misses), on cones, flat maps and patterns that wrap around their axis.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>
#include <set>
#include <tuple>

#include "cots_test_support.hpp"
#include "steady/core/errors.hpp"
#include "steady/cots/becots_range.hpp"

namespace {

using steady::Ball;
using steady::BecotsMap;
using steady::BecotsRangeFinder;
using steady::GroupRange;
using steady::InvalidInput;
using steady::PatternBall;
using steady::Vec3;

struct Tally {
  long long queries = 0, hits = 0, candidates = 0, groups = 0, misses = 0;
};

// Random queries around the range of `finder`'s map: near the surface, off it, small and large, compared with
// brute force.
void check_against_brute_force(const BecotsMap& map, const BecotsRangeFinder& finder, std::mt19937_64& rng,
                               int queries, Tally* tally) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), param(-0.1, 1.1), size(0.0, 1.0);
  const double scale = glm::length(map.a() - map.c()) + glm::length(map.b() - map.d());
  for (int q = 0; q < queries; ++q) {
    const double radius = q % 4 == 0 ? 0.0 : std::pow(size(rng), 3) * 0.3 * scale;  // points, small and large
    const Vec3 offset = Vec3(unit(rng), unit(rng), unit(rng)) * (0.1 * scale * size(rng));
    const Ball query{map.map(param(rng), param(rng)) + offset, radius};
    const std::vector<PatternBall> naive = finder.interfering_naive(query);
    std::set<std::pair<int, int>> covered;
    long long count = 0;
    for (const GroupRange& r : finder.candidates(query)) {
      count += r.count();
      for (int i = r.i0; i <= r.i1; ++i)
        for (int j = r.j0; j <= r.j1; ++j) covered.insert({i, j});
    }
    for (const PatternBall& b : naive) tally->misses += covered.count({b.i, b.j}) == 0;
    const std::vector<PatternBall> fast = finder.interfering(query);
    auto key = [](const PatternBall& b) { return std::make_tuple(b.i, b.j, b.n); };
    std::set<std::tuple<int, int, int>> a, b;
    for (const auto& p : naive) a.insert(key(p));
    for (const auto& p : fast) b.insert(key(p));
    EXPECT_EQ(a, b);
    EXPECT_EQ(fast.size(), b.size());  // each ball once
    tally->queries++;
    tally->hits += !naive.empty();
    tally->candidates += static_cast<long long>(covered.size());
    tally->groups += static_cast<long long>(finder.nu()) * finder.nv();
  }
}

// Template balls of group (0, 0): near M(s du, t dv), off the surface by up to their radius.
std::vector<Ball> template_balls(const BecotsMap& map, double du, double dv, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), param(0.0, 1.0);
  const double spacing = std::min(glm::length(map.map(du, 0) - map.a()), glm::length(map.map(0, dv) - map.a()));
  std::vector<Ball> balls;
  const int count = 1 + static_cast<int>(rng() % 3);
  for (int n = 0; n < count; ++n) {
    const double r = 0.35 * spacing * (0.5 + 0.5 * param(rng));
    balls.push_back({map.map(param(rng) * du, param(rng) * dv) + Vec3(unit(rng), unit(rng), unit(rng)) * (0.5 * r), r});
  }
  return balls;
}

TEST(BecotsRangeFinder, HoldsEveryInterferingGroupOnRandomPatterns) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Tally tally;
  int patterns = 0;
  for (int trial = 0; trial < 120; ++trial) {
    std::optional<BecotsMap> map;
    try {
      if (trial % 3 == 0) {
        map = BecotsMap({unit(rng), unit(rng), unit(rng)}, {unit(rng), unit(rng), unit(rng)},
                        {unit(rng), unit(rng), unit(rng)}, {unit(rng), unit(rng), unit(rng)});
      } else if (trial % 3 == 1) {  // wound fields: the pattern wraps around its axis
        const Vec3 apex{unit(rng), unit(rng), unit(rng)};
        map = BecotsMap::from_field(apex, {unit(rng), unit(rng), unit(rng)}, apex + 2.0 * Vec3(unit(rng), unit(rng), unit(rng)),
                                    {0.4 * unit(rng), 9.0 * unit(rng)}, {0.4 * unit(rng), 9.0 * unit(rng)});
      } else {  // flat: a planar COTS pattern of balls
        map = BecotsMap({unit(rng), unit(rng), 0.0}, {unit(rng), unit(rng), 0.0}, {unit(rng), unit(rng), 0.0},
                        {unit(rng), unit(rng), 0.0});
      }
    } catch (const InvalidInput&) {
      continue;
    }
    const int nu = 5 + static_cast<int>(rng() % 26), nv = 5 + static_cast<int>(rng() % 26);
    const double du = trial % 2 ? 1.0 / (nu - 1) : 1.0 / nu, dv = trial % 2 ? 1.0 / (nv - 1) : 1.0 / nv;
    const BecotsRangeFinder finder(*map, template_balls(*map, du, dv, rng), nu, nv, du, dv);
    check_against_brute_force(*map, finder, rng, 60, &tally);
    ++patterns;
  }
  EXPECT_GT(patterns, 100);
  EXPECT_EQ(tally.misses, 0);
  EXPECT_GT(tally.hits, tally.queries / 4);
  std::printf("[ measured ] BeCOTS RangeFinder: %d patterns, %lld queries (%lld hit a ball), %lld misses; candidate "
              "groups %.1f %% of all groups on average\n",
              patterns, tally.queries, tally.hits, tally.misses, 100.0 * tally.candidates / tally.groups);
}

TEST(BecotsRangeFinder, SmallQueriesOnALargePatternTestFewGroups) {
  // 1000 x 1000 groups of P1 bent onto a cone: a point query costs a handful of groups, not 10^6.
  const BecotsMap map = BecotsMap({0, 0, 0}, {0.1, 1, 0}, {1.3, 1.2, 0}, {1, 0, 0}).bent(0.7);
  const int n = 1000;
  const double step = 1.0 / (n - 1);
  const double r = 0.3 * glm::length(map.map(step, 0) - map.a());
  const BecotsRangeFinder finder(map, {{map.map(0.5 * step, 0.5 * step), r}}, n, n, step, step);
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> param(0.0, 1.0);
  long long largest = 0, hits = 0;
  for (int q = 0; q < 2000; ++q) {
    const double x = param(rng), y = param(rng);
    const Ball query{map.map(x, y), 0.0};
    long long count = 0;
    for (const GroupRange& g : finder.candidates(query)) count += g.count();
    largest = std::max(largest, count);
    // the group whose ball holds the query, if any, is among the candidates (checked exactly in its 3 x 3 block)
    const int i = static_cast<int>(std::lround(x / step - 0.5)), j = static_cast<int>(std::lround(y / step - 0.5));
    for (int di = -1; di <= 1; ++di)
      for (int dj = -1; dj <= 1; ++dj) {
        const int gi = i + di, gj = j + dj;
        if (gi < 0 || gj < 0 || gi >= n || gj >= n) continue;
        const Ball b = finder.ball(gi, gj, 0);
        if (glm::length(b.center - query.center) > b.radius) continue;
        ++hits;
        bool found = false;
        for (const GroupRange& g : finder.candidates(query))
          found |= gi >= g.i0 && gi <= g.i1 && gj >= g.j0 && gj <= g.j1;
        EXPECT_TRUE(found) << gi << " " << gj;
      }
  }
  EXPECT_GT(hits, 100);
  EXPECT_LE(largest, 16);
  std::printf("[ measured ] 1000 x 1000 BeCOTS pattern: at most %lld candidate groups per point query (of 10^6)\n", largest);
}

TEST(BecotsRangeFinder, QueriesOffTheShellAndThroughTheApex) {
  const BecotsMap map = BecotsMap({0, 0, 0}, {0.1, 1, 0}, {1.3, 1.2, 0}, {1, 0, 0}).bent(0.9);
  const BecotsRangeFinder finder(map, {{map.map(0.05, 0.05), 0.02}}, 10, 10, 0.1, 0.1);
  const Vec3 apex = *map.apex();
  // Far along the axis from the cone's sheet: outside the shell of cones the pattern spans.
  EXPECT_TRUE(finder.candidates({apex + 3.0 * map.axis(), 0.1}).empty());
  // A ball around the apex sees every group.
  const auto all = finder.candidates({apex, 0.5});
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].count(), 100);
  EXPECT_THROW(finder.candidates({apex, -1.0}), InvalidInput);
  // A flat parallelogram has no apex: its pattern is a translation lattice.
  const BecotsMap parallelogram({0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0});
  EXPECT_THROW(BecotsRangeFinder(parallelogram, {{{0.1, 0.1, 0}, 0.05}}, 4, 4, 0.25, 0.25), InvalidInput);
  EXPECT_THROW(BecotsRangeFinder(map, {}, 4, 4, 0.25, 0.25), InvalidInput);
  EXPECT_THROW(BecotsRangeFinder(map, {{{0.1, 0.1, 0}, 0.05}}, 0, 4, 0.25, 0.25), InvalidInput);
}

}  // namespace
