// BeCOTS lattices (slabs and raised stacks) as ordinary lattices: their balls sit where the map puts them, their
// hubs have the dissertation's degrees, and every query path agrees with brute force on them.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "query_oracle.hpp"
#include "steady/core/errors.hpp"
#include "steady/cots/becots_lattice.hpp"
#include "steady/lattice/lattice_io.hpp"
#include "steady/query/becots_query.hpp"
#include "steady/query/lattice_query.hpp"

namespace {

using namespace steady;

BecotsMap cone() { return BecotsMap({0, 0, 0}, {0.1, 1, 0.2}, {1.3, 1.2, -0.3}, {1, 0, 0.1}); }

TEST(BecotsLattice, BallsSitOnTheRaisedMaps) {
  const BecotsMap map = cone();
  for (const char* name : {"triangle", "kagome", "honeycomb"}) {
    const BecotsConnectivity cells = becots_connectivity(name);
    const Counts counts{6, 5, 3};
    const double raise = 0.04, radius = 0.03;
    const Lattice lattice = becots_lattice(map, cells, counts, radius, raise);
    EXPECT_EQ(lattice.layout().kind(), "any-order-brick");
    double worst = 0.0;
    for (std::int64_t k = 0; k < counts.w; ++k) {
      // Layer k is the pattern whose corner A, and template with it, is raised by k * raise along the axis: its
      // group origins lie on the raised map, and a node inside a cell follows its group's similarity.
      const BecotsMap layer = map.raised(static_cast<double>(k) * raise);
      for (std::int64_t j = 0; j < counts.v; ++j)
        for (std::int64_t i = 0; i < counts.u; ++i) {
          const Vec3 origin = layer.map(static_cast<double>(i) / counts.u, static_cast<double>(j) / counts.v);
          worst = std::max(worst, glm::length(map.field(static_cast<double>(i) / counts.u, static_cast<double>(j) / counts.v)
                                                  .apply_point(layer.a()) - origin));
          for (int n = 0; n < static_cast<int>(cells.nodes.size()); ++n) {
            const double s = cells.nodes[n].x / counts.u, t = cells.nodes[n].y / counts.v;
            const double x = i / static_cast<double>(counts.u) + s, y = j / static_cast<double>(counts.v) + t;
            const Ball b = lattice.ball({i, j, k, n});
            const Vec3 node = map.map(s, t) + static_cast<double>(k) * raise * map.axis();
            worst = std::max(worst, glm::length(b.center - map.field(x - s, y - t).apply_point(node)));
            if (k == 0) worst = std::max(worst, glm::length(b.center - map.map(x, y)));
            const double scale = std::exp(x * map.log_u().real() + y * map.log_v().real());
            worst = std::max(worst, std::abs(b.radius - radius * scale));
          }
        }
    }
    EXPECT_LT(worst, 1e-13) << name;
  }
}

TEST(BecotsLattice, HubsHaveTheDissertationsDegrees) {
  const std::map<std::string, std::vector<int>> degrees{{"triangle", {6}}, {"kagome", {4, 4, 4}}, {"honeycomb", {3, 3}}};
  for (const auto& [name, expected] : degrees) {
    const BecotsConnectivity cells = becots_connectivity(name);
    std::vector<int> degree(cells.nodes.size(), 0);
    for (const BeamPattern& b : cells.beams) degree[b.from]++, degree[b.to]++;
    EXPECT_EQ(degree, expected) << name;
    // An inner hub of the lattice: count the beams that end at one node of a middle group.
    const Lattice lattice = becots_lattice(cone(), cells, {7, 7, 1}, 0.01);
    const std::size_t m = static_cast<std::size_t>(lattice.beam_count());
    std::vector<std::int64_t> start(m), end(m);
    std::vector<double> r0(m), r1(m);
    lattice.beams(start.data(), end.data(), r0.data(), r1.data());
    for (int n = 0; n < static_cast<int>(cells.nodes.size()); ++n) {
      const std::int64_t hub = lattice.ball_index({3, 3, 0, n});
      int count = 0;
      for (std::size_t b = 0; b < m; ++b) count += (start[b] == hub) + (end[b] == hub);
      EXPECT_EQ(count, expected[n]) << name << " node " << n;
    }
  }
  EXPECT_THROW(becots_connectivity("square"), InvalidInput);
}

TEST(BecotsLattice, QueriesMatchBruteForceOnSlabsAndStacks) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u01(0.0, 1.0), unit(-1.0, 1.0);
  long queries = 0, hits = 0;
  const BecotsMap bent = BecotsMap({0, 0, 0}, {0.1, 1, 0}, {1.3, 1.2, 0}, {1, 0, 0}).bent(0.6);
  for (const BecotsMap& map : {cone(), bent}) {
    for (const Counts& counts : {Counts{12, 9, 1}, Counts{8, 6, 4}}) {
      const Lattice lattice = becots_lattice(map, becots_connectivity("kagome"), counts, 0.015, 0.05, 0.6);
      const LatticeQuery lq(lattice);
      const test::BruteForceQuery truth(lattice);
      std::vector<QueryMethod> methods = {QueryMethod::Auto, QueryMethod::Naive, QueryMethod::Rows, QueryMethod::Blocks};
      if (lq.plan().slabs_valid) methods.push_back(QueryMethod::Slabs);
      if (lq.plan().constant_valid) methods.push_back(QueryMethod::Constant);
      for (int q = 0; q < 120; ++q) {
        const Ball e = lattice.ball(lattice.ball_id(static_cast<std::int64_t>(u01(rng) * lattice.ball_count())));
        const Ball query{e.center + Vec3(unit(rng), unit(rng), unit(rng)) * (4.0 * e.radius), 3.0 * e.radius * u01(rng)};
        const BallQueryResult expected = truth(query);
        ++queries;
        hits += static_cast<long>(expected.balls.size() + expected.beams.size());
        for (QueryMethod m : methods) {
          const BallQueryResult got = lq.query_ball(query, m);
          EXPECT_EQ(got.balls, expected.balls) << to_string(m);
          EXPECT_EQ(got.beams, expected.beams) << to_string(m);
        }
      }
    }
  }
  EXPECT_GT(hits, queries / 2);
  std::printf("[ measured ] BeCOTS lattices: %ld queries (%ld hits), every query path equal to brute force\n", queries,
              hits);
}

TEST(BecotsLattice, TheMapLevelRangeFinderQueryEqualsNaive) {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> u01(0.0, 1.0), unit(-1.0, 1.0);
  const BecotsMap sheet({0, 0, 0}, {0.1, 1, 0}, {1.3, 1.2, 0}, {1, 0, 0});
  long queries = 0, hits = 0;
  std::int64_t candidates = 0, groups = 0;
  // a cone, a sheet wound more than once around its axis, a flat sheet; slabs and stacks joined between layers
  for (const BecotsMap& map : {cone(), sheet.bent(0.6), sheet.bent(0.08), sheet}) {
    for (const Counts& counts : {Counts{14, 10, 1}, Counts{9, 7, 3}}) {
      BecotsConnectivity cells = becots_connectivity("kagome");
      for (int n = 0; n < 3; ++n) {
        BeamPattern b;
        b.from = n, b.dk = 1, b.to = n;
        cells.beams.push_back(b);
      }
      const Lattice lattice = becots_lattice(map, cells, counts, 0.004, 0.02, 0.6);
      const LatticeQuery naive(lattice);
      const BecotsLatticeQuery fast(lattice, map);
      for (int q = 0; q < 100; ++q) {
        const Ball e = lattice.ball(lattice.ball_id(static_cast<std::int64_t>(u01(rng) * lattice.ball_count())));
        const double reach = q % 10 == 0 ? 0.3 : 0.02;  // now and then a large query
        const Ball query{e.center + Vec3(unit(rng), unit(rng), unit(rng)) * reach, reach * u01(rng)};
        const BallQueryResult expected = naive.query_ball(query, QueryMethod::Naive);
        const BallQueryResult got = fast.query_ball(query);
        EXPECT_EQ(got.balls, expected.balls);
        EXPECT_EQ(got.beams, expected.beams);
        ++queries;
        hits += static_cast<long>(expected.balls.size() + expected.beams.size());
        candidates += fast.candidate_groups(query);
        groups += counts.groups();
      }
    }
  }
  EXPECT_GT(hits, queries);
  std::printf("[ measured ] BecotsLatticeQuery: %ld queries (%ld hits) equal to naive; %.1f %% of the groups tested\n",
              queries, hits, 100.0 * candidates / groups);
  // Another map's lattice is refused.
  const Lattice other = becots_lattice(cone(), becots_connectivity("triangle"), {4, 4, 1}, 0.01);
  EXPECT_THROW(BecotsLatticeQuery(other, sheet.bent(0.6)), InvalidInput);
}

TEST(BecotsLattice, FileRoundTripAndBadInput) {
  const Lattice lattice = becots_lattice(cone(), becots_connectivity("triangle"), {4, 3, 2}, 0.02, 0.1);
  const Lattice back = lattice_from_json(lattice_to_json(lattice));
  EXPECT_EQ(back.ball_count(), lattice.ball_count());
  EXPECT_LT(glm::length(back.ball({3, 2, 1, 0}).center - lattice.ball({3, 2, 1, 0}).center), 1e-12);
  EXPECT_THROW(becots_lattice(cone(), becots_connectivity("triangle"), {4, 3, 2}, 0.02, 0.0), InvalidInput);
  EXPECT_THROW(becots_lattice(cone(), becots_connectivity("triangle"), {4, 3, 1}, -1.0), InvalidInput);
  EXPECT_THROW(becots_lattice(cone(), becots_connectivity("triangle"), {4, 3, 1}, 0.02, 0.0, 1.5), InvalidInput);
}

}  // namespace
