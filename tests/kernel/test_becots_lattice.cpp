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
      EXPECT_TRUE(lq.plan().becots_valid) << lq.plan().becots_reason;
      EXPECT_EQ(lq.plan().automatic, QueryMethod::Becots);
      methods.push_back(QueryMethod::Becots);
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

TEST(BecotsLattice, NormalOffsetLayersMoveCornerAAlongTheNormal) {
  // 6.3 (b): every layer shares the field, its corner A moved by k d along the range's normal at A. The normal is
  // orthogonal to both derivatives of the map at (0, 0) (difference quotients) and lies in the plane of A and the axis.
  const BecotsMap map = cone();
  const Vec3 n = map.normal(), a = map.a(), axis = map.axis(), apex = *map.apex();
  const double h = 1e-6;
  const Vec3 dx = (map.map(h, 0.0) - map.map(-h, 0.0)) / (2.0 * h), dy = (map.map(0.0, h) - map.map(0.0, -h)) / (2.0 * h);
  EXPECT_NEAR(glm::length(n), 1.0, 1e-15);
  EXPECT_LT(std::abs(glm::dot(n, glm::normalize(dx))), 1e-9);
  EXPECT_LT(std::abs(glm::dot(n, glm::normalize(dy))), 1e-9);
  EXPECT_GT(glm::dot(n, glm::cross(dx, dy)), 0.0);
  EXPECT_LT(std::abs(glm::dot(n, glm::normalize(glm::cross(axis, a - apex)))), 1e-12);
  const BecotsConnectivity cells = becots_connectivity("triangle");
  const Counts counts{7, 5, 4};
  const double offset = 0.03;
  const Lattice lattice = becots_lattice(map, cells, counts, 0.01, 0.0, 0.5, offset);
  double worst = 0.0;
  for (std::int64_t k = 0; k < counts.w; ++k) {
    // Layer k is the BeCOTS map of the same field through A + k d N.
    const BecotsMap layer = BecotsMap::from_field(apex, axis, a + static_cast<double>(k) * offset * n, map.log_u(),
                                                  map.log_v());
    for (std::int64_t j = 0; j < counts.v; ++j)
      for (std::int64_t i = 0; i < counts.u; ++i)
        worst = std::max(worst, glm::length(lattice.ball({i, j, k, 0}).center -
                                            layer.map(static_cast<double>(i) / counts.u,
                                                      static_cast<double>(j) / counts.v)));
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_THROW(becots_lattice(map, cells, counts, 0.01, 0.0, 0.5, NAN), InvalidInput);
}

TEST(BecotsLattice, StackQueriesSearchOnlyTheLayersNearTheQuery) {
  // The dissertation's O(1) stack query: only the layers whose shell of cones meets the query's are searched, for
  // raised and for normal-offset stacks, and the answers equal brute force. LatticeQuery takes this path on its
  // own.
  std::mt19937_64 rng(47);
  std::uniform_real_distribution<double> u01(0.0, 1.0), unit(-1.0, 1.0);
  BecotsConnectivity cells = becots_connectivity("kagome");
  for (int n = 0; n < 3; ++n) {
    BeamPattern b;
    b.from = n, b.dk = 1, b.to = n;
    cells.beams.push_back(b);
  }
  const BecotsMap bent = BecotsMap({0, 0, 0}, {0.1, 1, 0}, {1.3, 1.2, 0}, {1, 0, 0}).bent(0.6);
  struct Case {
    BecotsMap map;
    double raise, offset;
  };
  long queries = 0, layers_searched = 0, point_queries = 0;
  std::map<std::int64_t, long> most_layers;  // by the number of layers: the most a point query searched
  for (const std::int64_t layers : {10, 40})
    for (const Case& c : {Case{cone(), 0.02, 0.0}, Case{cone(), 0.0, 0.02}, Case{bent, 0.0, -0.015},
                          Case{bent, 0.01, 0.01}}) {
      const Counts counts{10, 8, layers};
      const Lattice lattice = becots_lattice(c.map, cells, counts, 0.004, c.raise, 0.6, c.offset);
      const BecotsLatticeQuery fast(lattice, c.map);
      const LatticeQuery lq(lattice);
      ASSERT_TRUE(lq.plan().becots_valid) << lq.plan().becots_reason;
      const test::BruteForceQuery truth(lattice);
      for (int q = 0; q < 100; ++q) {
        const Ball e = lattice.ball(lattice.ball_id(static_cast<std::int64_t>(u01(rng) * lattice.ball_count())));
        const bool point = q % 2 == 0;
        const Ball query{e.center + Vec3(unit(rng), unit(rng), unit(rng)) * (2.0 * e.radius),
                         point ? 0.0 : 2.0 * e.radius * u01(rng)};
        const BallQueryResult expected = truth(query);
        for (const BallQueryResult& got : {fast.query_ball(query), lq.query_ball(query)}) {
          EXPECT_EQ(got.balls, expected.balls);
          EXPECT_EQ(got.beams, expected.beams);
        }
        const long searched = static_cast<long>(fast.candidate_layers(query).size());
        ++queries;
        layers_searched += searched;
        if (point) {
          ++point_queries;
          most_layers[layers] = std::max(most_layers[layers], searched);
        }
      }
    }
  // A layer's elements reach the next layer's (the joining beams), and a raised layer is not on one cone (its
  // template moves rigidly), so a point sees a handful of layers, about as many in a stack of 40 as in one of 10
  // (other queries, and the table's buckets fall elsewhere: one more is allowed).
  EXPECT_LE(most_layers[40], most_layers[10] + 1);
  EXPECT_LE(most_layers[40], 8);
  std::printf("[ measured ] BeCOTS stacks of 10 and 40 layers: %ld queries equal to brute force; %.2f layers "
              "searched per query on average; a point query searched at most %ld of 10 layers, %ld of 40\n",
              queries, static_cast<double>(layers_searched) / queries, most_layers[10], most_layers[40]);
}

TEST(BecotsLattice, LatticeQueryFindsTheMapOrSaysWhyNot) {
  // The BeCOTS path needs the map: found from the steps of any lattice laid on one (however made), refused with
  // a reason otherwise.
  const BecotsMap map = cone();
  const Lattice laid = becots_lattice(map, becots_connectivity("honeycomb"), {5, 4, 1}, 0.01);
  const Lattice by_hand = Lattice::incremental(laid.definition().nodes, laid.definition().beams, {5, 4, 1},
                                               map.field(0.2, 0.0), map.field(0.0, 0.25), Similarity::identity());
  for (const Lattice* l : {&laid, &by_hand}) {
    const LatticeQuery lq(*l);
    EXPECT_TRUE(lq.plan().becots_valid) << lq.plan().becots_reason;
    EXPECT_EQ(lq.plan().automatic, QueryMethod::Becots);
    EXPECT_NE(lq.plan().describe().find("becots (O(1) on a BeCOTS slab or stack): yes"), std::string::npos);
  }
  // A screw and a translation (a lattice on a cylinder): no apex.
  const Lattice cylinder = Lattice::incremental({{{1, 0, 0}, 0.1}}, {}, {6, 4, 1},
                                                Similarity::rotation(0.3, {0, 0, 1}, {0, 0, 0}),
                                                Similarity::translation({0, 0, 0.5}), Similarity::identity());
  const LatticeQuery lq(cylinder);
  EXPECT_FALSE(lq.plan().becots_valid);
  EXPECT_NE(lq.plan().becots_reason.find("no apex"), std::string::npos) << lq.plan().becots_reason;
  EXPECT_THROW(lq.query_ball({{1, 0, 0}, 0.1}, QueryMethod::Becots), InvalidInput);
  // Layers moved last (after U and V) are not a BeCOTS stack.
  const Lattice last = Lattice::incremental(laid.definition().nodes, laid.definition().beams, {5, 4, 3},
                                            map.field(0.2, 0.0), map.field(0.0, 0.25),
                                            Similarity::translation(0.05 * map.axis()));
  EXPECT_FALSE(LatticeQuery(last).plan().becots_valid);
  EXPECT_EQ(query_method_from_string("becots"), QueryMethod::Becots);
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
