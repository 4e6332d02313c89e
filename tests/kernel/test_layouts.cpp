// Layouts: the steady brick, the steady brick with its steps applied in any order, and a table of one
// similarity per group. Each is checked against an independent composition of its definition; the fast
// paths (queries, sums, clean check) on reordered bricks against brute force and against the same lattice as
// a table (which takes the general paths); the file format round-trips every kind exactly.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <random>
#include <set>

#include "query_oracle.hpp"
#include "sample_lattices.hpp"
#include "steady/core/errors.hpp"
#include "steady/lattice/any_order_layout.hpp"
#include "steady/lattice/lattice_io.hpp"
#include "steady/lattice/table_layout.hpp"
#include "steady/properties/lattice_properties.hpp"
#include "steady/query/hub_overlaps.hpp"
#include "test_support.hpp"

namespace steady {
namespace {

const AxisOrder kAllOrders[6] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};

bool same_bits(const Ball& a, const Ball& b) {
  return std::memcmp(&a.center, &b.center, sizeof a.center) == 0 && std::memcmp(&a.radius, &b.radius, sizeof a.radius) == 0;
}

// A graded lattice (two nodes, beams along every direction and diagonals, explicit radii on some) whose
// steps apply in `order`; steps small enough for the lattice to stay clean in every order.
Lattice graded(const AxisOrder& order, Counts counts = {5, 4, 3}, std::vector<NodeId> omitted = {}) {
  const std::vector<TemplateNode> nodes = {{{0, 0, 0}, 0.1}, {{0.5, 0.5, 0.5}, 0.08}};
  const std::vector<BeamPattern> beams = {{0, 1, 0, 0, 0}, {0, 0, 1, 0, 0}, {0, 0, 0, 1, 0},
                                          {1, 0, 0, 0, 0, 0.04, 0.03}, {1, 1, 1, 1, 0, 0.03, 0.03}};
  const DirectionControl U{Similarity::swirl(0.06, {0, 0, 1}, {0, 16.7, 0}, 1.02)};
  const DirectionControl V{Similarity::screw(0.05, {0, 1, 0}, {1.5, 0, 1}, 1.0)};
  const DirectionControl W{Similarity::rotation(0.04, {1, 0, 0}, {0, -25, 0})};
  const Similarity G = Similarity::rotation(0.7, {1, 2, 3}, {0.5, 0, 0}) * Similarity::dilation(1.5, {0, 0, 0});
  return Lattice::ordered(nodes, beams, counts, U, V, W, G, order, std::move(omitted));
}

// G o X3^a3 o X2^a2 o X1^a1 with X_b the step applied b-th: the definition, composed by hand.
Similarity composed(const Lattice& lat, const AxisOrder& order, std::int64_t i, std::int64_t j, std::int64_t k) {
  const SteadyBrick& brick = *lat.layout().steady_brick();
  const std::int64_t index[3] = {i, j, k};
  Similarity s = brick.placement;
  for (int b = 2; b >= 0; --b) s = s * brick.step_along(order[b]).power(static_cast<double>(index[order[b]]));
  return s;
}

TEST(Layouts, AnyOrderPlacesEveryGroupByItsOrderOfApplication) {
  for (const AxisOrder& order : kAllOrders) {
    const Lattice lat = graded(order);
    EXPECT_EQ(lat.layout().kind(), order == kUVW ? "steady-brick" : "any-order-brick");
    const Counts& c = lat.counts();
    for (std::int64_t k = 0; k < c.w; ++k)
      for (std::int64_t j = 0; j < c.v; ++j)
        for (std::int64_t i = 0; i < c.u; ++i)
          EXPECT_LT(lat.group_similarity(i, j, k).map_distance(composed(lat, order, i, j, k)), 1e-12)
              << to_string(order) << " group " << i << "," << j << "," << k;
  }
  // The orders really differ: the last applied step acts on the whole lattice.
  EXPECT_GT(glm::length(graded({0, 1, 2}).ball({4, 3, 2, 0}).center - graded({2, 1, 0}).ball({4, 3, 2, 0}).center), 0.05);
}

TEST(Layouts, BrickLatticeIsTheSameGroupsReindexed) {
  for (const AxisOrder& order : kAllOrders) {
    const Lattice lat = graded(order, {5, 4, 3}, {{1, 2, 0, 1}, {4, 0, 2, 0}});
    const Lattice* brick = lat.brick_lattice();
    ASSERT_NE(brick, nullptr);
    EXPECT_EQ(brick == &lat, order == kUVW);
    EXPECT_FALSE(brick->layout().steady_brick()->reordered());
    ASSERT_EQ(brick->ball_count(), lat.ball_count());
    ASSERT_EQ(brick->beam_count(), lat.beam_count());
    for (std::int64_t q = 0; q < lat.ball_count(); ++q) {
      const NodeId id = lat.ball_id(q);
      EXPECT_EQ(lat.from_brick(lat.to_brick(id)), id);
      EXPECT_TRUE(same_bits(lat.ball(id), brick->ball(lat.to_brick(id)))) << to_string(order);
    }
    for (std::int64_t q = 0; q < lat.beam_count(); ++q) {
      const BeamId id = lat.beam_id(q);
      ASSERT_TRUE(brick->beam_exists(lat.to_brick(id)));
      const BeamGeometry a = lat.beam(id), b = brick->beam(lat.to_brick(id));
      EXPECT_TRUE(same_bits(a.start, b.start) && same_bits(a.end, b.end));
    }
  }
}

TEST(Layouts, QueriesOnEveryOrderAndOnATableMatchBruteForce) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  long queries = 0, hits = 0;
  for (const AxisOrder& order : kAllOrders) {
    const Lattice ordered = graded(order, {6, 5, 4}, {{2, 2, 1, 0}});
    const Lattice table = ordered.with_layout(TableLayout::of(ordered.layout()));
    for (const Lattice* lat : {&ordered, &table}) {
      const LatticeQuery lq(*lat);
      const test::BruteForceQuery truth(*lat);
      std::vector<QueryMethod> methods = {QueryMethod::Auto, QueryMethod::Naive};
      if (lat == &ordered) {
        methods.insert(methods.end(), {QueryMethod::Rows, QueryMethod::Blocks});
        if (lq.plan().slabs_valid) methods.push_back(QueryMethod::Slabs);
        if (lq.plan().constant_valid) methods.push_back(QueryMethod::Constant);
      } else {
        EXPECT_FALSE(lq.plan().steady_reason.empty());
        EXPECT_THROW(lq.resolve(QueryMethod::Rows), InvalidInput);
      }
      for (int q = 0; q < 150; ++q) {
        const Ball e = lat->ball(lat->ball_id(static_cast<std::int64_t>(u01(rng) * static_cast<double>(lat->ball_count()))));
        const Ball query{e.center + test::random_vec(rng, 4.0 * e.radius), 3.0 * e.radius * u01(rng)};
        const BallQueryResult expected = truth(query);
        ++queries;
        hits += static_cast<long>(expected.balls.size() + expected.beams.size());
        for (QueryMethod m : methods) {
          const BallQueryResult got = lq.query_ball(query, m);
          EXPECT_EQ(got.balls, expected.balls) << to_string(order) << " " << to_string(m);
          EXPECT_EQ(got.beams, expected.beams) << to_string(order) << " " << to_string(m);
        }
      }
    }
  }
  EXPECT_GT(hits, queries);  // most queries meet several elements
  std::printf("[ layouts ] %ld queries on reordered bricks and tables, %ld hits\n", queries, hits);
}

TEST(Layouts, PropertiesOfEveryOrderMatchTheTableAndBruteForce) {
  for (const AxisOrder& order : kAllOrders) {
    const Lattice ordered = graded(order, {5, 4, 3}, {{1, 1, 1, 0}});
    const Lattice table = ordered.with_layout(TableLayout::of(ordered.layout()));
    const LatticeProperties fast = lattice_properties(ordered), general = lattice_properties(table),
                            brute = lattice_properties_brute_force(ordered);
    ASSERT_TRUE(fast.clean_verified && general.clean_verified);
    ASSERT_EQ(fast.overlap_count + general.overlap_count, 0);
    // Hubs whose stumps overlap are integrated by quadrature (1e-12 relative per hub): 1e-10 overall.
    EXPECT_NEAR(fast.volume, brute.volume, 1e-10 * brute.volume) << to_string(order);
    EXPECT_NEAR(general.volume, brute.volume, 1e-10 * brute.volume) << to_string(order);
    EXPECT_NEAR(fast.area, brute.area, 1e-10 * brute.area);
    const double size = std::cbrt(brute.volume);
    EXPECT_LT(glm::length(fast.centroid - brute.centroid), 1e-10 * size);
    EXPECT_LT(glm::length(general.centroid - brute.centroid), 1e-10 * size);
    EXPECT_LT(test::max_abs(fast.inertia - brute.inertia), 1e-10 * test::max_abs(brute.inertia));
    EXPECT_LT(test::max_abs(general.inertia - brute.inertia), 1e-10 * test::max_abs(brute.inertia));
    // the sums ran on the brick (distinct shapes), the table on every hub
    EXPECT_LT(fast.hub_shapes, general.hub_shapes);
  }
}

TEST(Layouts, HubOverlapsAreNamedInTheLatticesOwnIndices) {
  // Thick nodes: overlapping hubs, found through the slab window of the brick lattice and reported with
  // this lattice's indices (the same pairs the table lattice reports from comparing every hub).
  for (const AxisOrder& order : {AxisOrder{2, 0, 1}, AxisOrder{1, 2, 0}}) {
    const Lattice base = graded(order, {4, 3, 3});
    LatticeDefinition d = base.definition();
    d.nodes[1].radius = 0.4;
    const Lattice thick(d);
    const Lattice table = thick.with_layout(TableLayout::of(thick.layout()));
    const HubOverlapReport a = check_hub_overlaps(thick, 1000, no_progress(), HubOverlapCheckMethod::SlabWindow);
    const HubOverlapReport b = check_hub_overlaps(table, 1000, no_progress(), HubOverlapCheckMethod::AllHubs);
    ASSERT_GT(b.overlap_count, 0);
    EXPECT_EQ(a.overlap_count, b.overlap_count);
    // The slab window lists one representative pair per class of similar pairs; each must be a real pair.
    auto key = [](const HubOverlap& o) {
      std::string a = to_string(o.a), b = to_string(o.b);
      return a < b ? std::make_pair(a, b) : std::make_pair(b, a);
    };
    std::set<std::pair<std::string, std::string>> all;
    for (const HubOverlap& o : b.overlaps) all.insert(key(o));
    ASSERT_EQ(static_cast<std::int64_t>(all.size()), b.overlap_count);
    for (const HubOverlap& o : a.overlaps) EXPECT_EQ(all.count(key(o)), 1u) << to_string(o.a) << " " << to_string(o.b);
    EXPECT_THROW(check_hub_overlaps(table, 10, no_progress(), HubOverlapCheckMethod::SlabWindow), InvalidInput);
  }
}

TEST(Layouts, FilesRoundTripEveryKindExactly) {
  const Lattice ordered = graded({1, 2, 0}, {5, 4, 3}, {{1, 2, 0, 1}});
  const Lattice table = ordered.with_layout(TableLayout::of(ordered.layout()));
  for (const Lattice* lat : {&ordered, &table}) {
    const std::string text = lattice_to_json(*lat);
    const Lattice again = lattice_from_json(text);
    EXPECT_EQ(again.layout().kind(), lat->layout().kind());
    EXPECT_EQ(lattice_to_json(again), text);
    for (std::int64_t q = 0; q < lat->ball_count(); ++q)
      EXPECT_TRUE(same_bits(lat->ball(lat->ball_id(q)), again.ball(again.ball_id(q))));
  }
  EXPECT_NE(lattice_to_json(ordered).find("\"order\": \"VWU\""), std::string::npos);
}

TEST(Layouts, ChangingCountsKeepsTheDefinition) {
  const Lattice ordered = graded({2, 0, 1});
  const LayoutPtr bigger = ordered.layout().with_counts({7, 6, 5});
  const Lattice grown = ordered.with_layout(bigger);
  EXPECT_EQ(grown.counts().u, 7);
  for (std::int64_t i = 0; i < 5; ++i)
    EXPECT_TRUE(same_bits(grown.ball({i, 1, 2, 0}), ordered.ball({i, 1, 2, 0})));
  const LayoutPtr table = TableLayout::of(ordered.layout());
  EXPECT_THROW(table->with_counts({7, 6, 5}), InvalidInput);
  // placed(G) moves every group by G
  const Similarity G = Similarity::screw(0.3, {0, 0, 1}, {1, 1, 0}, 2.0);
  for (const Lattice* lat : {&ordered}) {
    const Lattice moved = lat->placed(G);
    for (std::int64_t q = 0; q < lat->ball_count(); q += 7) {
      const Ball a = G.apply(lat->ball(lat->ball_id(q))), b = moved.ball(moved.ball_id(q));
      EXPECT_LT(glm::length(a.center - b.center), 1e-12 * (1.0 + glm::length(a.center)));
    }
  }
}

TEST(Layouts, BadLayoutsAreRefusedNamingTheField) {
  auto message = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message([] { TableLayout::make({2, 2, 1}, {Similarity::identity()}); }).find("similarities: a table layout"),
            std::string::npos);
  EXPECT_NE(message([] { TableLayout::make({0, 2, 1}, {}); }).find("counts.u: must be >= 1"), std::string::npos);
  EXPECT_NE(message([] { axis_order_from_string("UUW", "order"); }).find("order: \"UUW\" is not an order"),
            std::string::npos);
  EXPECT_NE(message([] { axis_order_from_string("UV", "order"); }).find("order:"), std::string::npos);
  EXPECT_NE(message([] {
              SteadyBrickLayout::steps({1000, 1, 1}, Similarity::dilation(3.0, {0, 0, 0}), Similarity::identity(),
                                       Similarity::identity());
            }).find("U, V, W: the scales compound"),
            std::string::npos);
  EXPECT_NE(message([] { Lattice({{{{0, 0, 0}, 1.0}}, {}, nullptr, {}}); }).find("layout:"), std::string::npos);
}

}  // namespace
}  // namespace steady
