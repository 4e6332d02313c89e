// Ball-interference queries on lattices: every path (naive, rows, slabs, constant, blocks) returns
// exactly the brute-force set over Lattice::ball/beam with the exact predicates, on random steady bricks
// (every kind of step, near-identity steps, omitted nodes, explicit beam radii) and on the benchmark
// lattice classes; the fast-path conditions are detected where they hold and refused where they do not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <random>

#include "test_support.hpp"
#include "query_oracle.hpp"
#include "sample_lattices.hpp"
#include "steady/core/errors.hpp"
#include "steady/query/interference.hpp"
#include "steady/query/lattice_query.hpp"
#include "steady/lattice/lattice_io.hpp"

namespace steady {
namespace {

// Query balls near random elements (so that most queries hit something), some touching exactly, some
// points, some anywhere in the bound.
std::vector<Ball> sample_queries(const Lattice& lat, const LatticeQuery& lq, std::mt19937_64& rng, int count) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::vector<Ball> out;
  const Ball bound = lq.bound();
  for (int q = 0; q < count; ++q) {
    Ball b;
    if (q % 5 == 4 || lat.ball_count() == 0) {
      b.center = bound.center + test::random_vec(rng, bound.radius);
      b.radius = u01(rng) * 0.3 * bound.radius / std::cbrt(static_cast<double>(std::max<std::int64_t>(1, lat.ball_count())));
    } else {
      const Ball e = lat.ball(lat.ball_id(static_cast<std::int64_t>(u01(rng) * lat.ball_count())));
      b.center = e.center + test::random_vec(rng, 3.0 * e.radius);
      b.radius = q % 7 == 0 ? 0.0 : 2.0 * e.radius * u01(rng);
      if (q % 11 == 0) b.radius = std::max(0.0, glm::length(b.center - e.center) - e.radius);  // touching
    }
    out.push_back(b);
  }
  return out;
}

struct Tally {
  long queries = 0, hits = 0, mismatches = 0, slabs = 0, constant = 0, lattices = 0;
};

void compare_paths(const Lattice& lat, std::mt19937_64& rng, int queries, Tally& t, const std::string& label) {
  const LatticeQuery lq(lat);
  std::vector<QueryMethod> methods = {QueryMethod::Naive, QueryMethod::Rows, QueryMethod::PaperRows,
                                      QueryMethod::Blocks, QueryMethod::Auto};
  if (lq.plan().slabs_valid) {
    methods.push_back(QueryMethod::Slabs);
    methods.push_back(QueryMethod::PaperSlabs);
  }
  if (lq.plan().constant_valid) methods.push_back(QueryMethod::Constant);
  ++t.lattices;
  t.slabs += lq.plan().slabs_valid;
  t.constant += lq.plan().constant_valid;
  const test::BruteForceQuery brute_force(lat);
  for (const Ball& q : sample_queries(lat, lq, rng, queries)) {
    const BallQueryResult truth = brute_force(q);
    ++t.queries;
    t.hits += static_cast<long>(truth.balls.size() + truth.beams.size());
    for (QueryMethod m : methods) {
      const BallQueryResult r = lq.query_ball(q, m);
      if (r.balls != truth.balls || r.beams != truth.beams) {
        ++t.mismatches;
        ADD_FAILURE() << label << ": method " << to_string(m) << " gives " << r.balls.size() << "+" << r.beams.size()
                      << " elements, brute force " << truth.balls.size() << "+" << truth.beams.size() << " (query "
                      << q.center.x << "," << q.center.y << "," << q.center.z << " r " << q.radius << ")";
      }
      const bool any = !truth.balls.empty() || !truth.beams.empty();
      if (lq.touches(q, m) != any) {
        ++t.mismatches;
        ADD_FAILURE() << label << ": touches() disagrees for method " << to_string(m);
      }
    }
  }
}

TEST(LatticeQuery, AllPathsMatchBruteForceOnRandomLattices) {
  std::mt19937_64 rng(2024);
  Tally t;
  for (int l = 0; l < 700; ++l) {
    const Lattice lat = test::random_lattice(rng, l);
    if (lat.ball_count() == 0) continue;
    compare_paths(lat, rng, 60, t, "random lattice " + std::to_string(l));
  }
  EXPECT_EQ(t.mismatches, 0);
  EXPECT_GT(t.queries, 40000);
  std::printf("[ lattice ] %ld random-lattice queries, %ld hits, %ld mismatches; %ld lattices, O(u) on %ld, O(1) on %ld\n",
              t.queries, t.hits, t.mismatches, t.lattices, t.slabs, t.constant);
  EXPECT_GT(t.slabs, 50);
  EXPECT_GT(t.constant, 20);
}

TEST(LatticeQuery, AllPathsMatchBruteForceOnBenchmarkClasses) {
  std::mt19937_64 rng(77);
  Tally t;
  compare_paths(test::regular_bcc({5, 4, 6}), rng, 1500, t, "regular");
  compare_paths(test::sheared_cubic({6, 5, 4}), rng, 1500, t, "sheared");
  compare_paths(test::cylindrical_bcc({4, 12, 6}), rng, 1500, t, "cylindrical");
  compare_paths(test::cylindrical_bcc({3, 40, 3}), rng, 1000, t, "cylindrical full turn");
  compare_paths(test::bent_twisted_tapered({6, 5, 7}), rng, 1500, t, "bent-twisted-tapered");
  // Wrapping rows: W turns 2.9 rad per step about an axis through the lattice.
  compare_paths(Lattice::incremental({{{3, 0, 0}, 0.3}, {{3.5, 0.2, 0.1}, 0.2}}, {{0, 0, 0, 0, 1}, {0, 0, 0, 1, 1, 0.1, 0.1}},
                                     {3, 2, 25}, Similarity::translation({0, 0, 2}), Similarity::dilation(1.3, {0, 0, 0}),
                                     Similarity::rotation(2.9, {0, 0, 1}, {0, 0, 0})),
                rng, 1500, t, "wrapping");
  // Rotation near 2 pi per step (principal angle -1e-4) and a near-identity swirl.
  compare_paths(Lattice::incremental({{{4, 0, 0}, 0.05}}, test::cubic_patterns(), {4, 3, 30},
                                     Similarity::translation({0.3, 0, 0}), Similarity::translation({0, 0, 0.3}),
                                     Similarity::rotation(2 * kPi - 1e-4, {0, 0, 1}, {0, 0, 0})),
                rng, 1500, t, "near full turn");
  compare_paths(Lattice::incremental({{{4, 0, 0}, 0.05}}, test::cubic_patterns(), {4, 3, 30},
                                     Similarity::translation({0.3, 0, 0}), Similarity::translation({0, 0.3, 0}),
                                     Similarity::swirl(1e-9, {0, 0, 1}, {0, 0, 0}, std::exp(1e-9)) *
                                         Similarity::translation({0, 0, 0.2})),
                rng, 1500, t, "near identity");
  EXPECT_EQ(t.mismatches, 0);
  std::printf("[ lattice ] %ld benchmark-class queries, %ld hits, %ld mismatches\n", t.queries, t.hits, t.mismatches);
}

TEST(LatticeQuery, AStepTooSteepForTheFastPathsTablesLeavesTheNaivePath) {
  // Found by fuzz_lattice_json's short run: a dilation of 150 a step over 4 groups and a pattern offset of 9 (no
  // beam of it in the lattice). The fast paths tabulate U^i up to 9 groups beyond the lattice, where U^12 is out
  // of the numerical range, and LatticeQuery refused the lattice (ValueError: "similarity: its translation: is
  // 6.9e+18, beyond the supported range") though every element of it is in range. The naive path answers, and the
  // plan says why.
  const Lattice lat = lattice_from_json(test::file_bytes(std::string(STEADY_TEST_DATA) + "/fuzz/lattice_steep_dilation_far_pattern.json"));
  const LatticeQuery lq(lat);
  EXPECT_EQ(lq.plan().automatic, QueryMethod::Naive);
  EXPECT_NE(lq.plan().steady_reason.find("out of range"), std::string::npos) << lq.plan().steady_reason;
  EXPECT_THROW(lq.query_ball({Vec3(0.0), 0.0}, QueryMethod::Blocks), InvalidInput);  // says why it does not apply
  const test::BruteForceQuery brute_force(lat);
  std::mt19937_64 rng(7);
  for (const Ball& q : sample_queries(lat, lq, rng, 40)) {
    const BallQueryResult truth = brute_force(q), r = lq.query_ball(q);
    EXPECT_EQ(r.balls, truth.balls);
    EXPECT_EQ(r.beams, truth.beams);
  }
  const Ball first = lat.ball(lat.ball_id(0));
  EXPECT_EQ(lq.query_ball({first.center, 0.0}).balls.front(), 0);
}

TEST(LatticeQuery, LongFuzz) {
  if (!std::getenv("STEADY_LONG_TESTS")) GTEST_SKIP() << "set STEADY_LONG_TESTS=1";
  std::mt19937_64 rng(99);
  Tally t;
  for (int l = 0; l < 20000; ++l) {
    const Lattice lat = test::random_lattice(rng, l, {7, true, true});
    if (lat.ball_count() == 0) continue;
    compare_paths(lat, rng, 60, t, "random lattice " + std::to_string(l));
  }
  EXPECT_EQ(t.mismatches, 0);
  std::printf("[ lattice ] %ld random-lattice queries, %ld hits, %ld mismatches\n", t.queries, t.hits, t.mismatches);
}

TEST(LatticeQuery, HitGeometryIsTheLatticeGeometry) {
  std::mt19937_64 rng(5);
  struct Check : HitSink {
    const Lattice* lat;
    int checked = 0;
    bool on_hit(const ElementHit& h) override {
      if (h.is_beam) {
        const BeamGeometry g = lat->beam(lat->beam_id(h.index));
        EXPECT_EQ(g.start.center, h.beam.start.center);
        EXPECT_EQ(g.end.center, h.beam.end.center);
        EXPECT_EQ(g.start.radius, h.beam.start.radius);
        EXPECT_EQ(g.end.radius, h.beam.end.radius);
      } else {
        const Ball b = lat->ball(lat->ball_id(h.index));
        EXPECT_EQ(b.center, h.ball.center);  // bit for bit
        EXPECT_EQ(b.radius, h.ball.radius);
      }
      ++checked;
      return true;
    }
  };
  int total = 0;
  for (int l = 0; l < 100; ++l) {
    const Lattice lat = test::random_lattice(rng, l);
    const LatticeQuery lq(lat);
    for (const Ball& q : sample_queries(lat, lq, rng, 20)) {
      for (QueryMethod m : {QueryMethod::Naive, QueryMethod::Rows, QueryMethod::Blocks}) {
        Check c;
        c.lat = &lat;
        lq.visit(q, c, m);
        total += c.checked;
      }
    }
  }
  EXPECT_GT(total, 1000);
}

TEST(LatticeQuery, DetectsFastPathConditions) {
  const LatticeQuery regular(test::regular_bcc({4, 4, 4}));
  EXPECT_TRUE(regular.plan().constant_valid) << regular.plan().describe();
  EXPECT_TRUE(regular.plan().slabs_valid);
  EXPECT_EQ(regular.plan().automatic, QueryMethod::Constant);
  // Sheared translations break the paper's condition; the dual directions restore O(1).
  const LatticeQuery sheared(test::sheared_cubic({4, 4, 4}));
  EXPECT_TRUE(sheared.plan().constant_valid) << sheared.plan().describe();
  // Cylindrical: the paper's O(u); the distance to the axis (a line through U's fixed point) gives O(1).
  const LatticeQuery cyl(test::cylindrical_bcc({4, 16, 4}));
  EXPECT_TRUE(cyl.plan().slabs_valid) << cyl.plan().describe();
  EXPECT_TRUE(cyl.plan().constant_valid) << cyl.plan().describe();
  EXPECT_NE(cyl.plan().constant_u.find(NormalizedMap::Type::AxisDilation), nullptr);
  // Bent, twisted, tapered: nothing commutes.
  const LatticeQuery btt(test::bent_twisted_tapered({5, 5, 5}));
  EXPECT_FALSE(btt.plan().slabs_valid);
  EXPECT_FALSE(btt.plan().constant_valid);
  EXPECT_EQ(btt.plan().automatic, QueryMethod::Blocks);
  EXPECT_THROW(btt.query_ball({{0, 0, 0}, 1.0}, QueryMethod::Constant), InvalidInput);
  EXPECT_THROW(btt.query_ball({{0, 0, 0}, 1.0}, QueryMethod::Slabs), InvalidInput);
}

TEST(LatticeQuery, RejectsBadQueries) {
  const Lattice lat = test::regular_bcc({2, 2, 2});
  const LatticeQuery lq(lat);
  const double nan = std::nan("");
  EXPECT_THROW(lq.query_ball({{nan, 0, 0}, 1.0}), InvalidInput);
  EXPECT_THROW(lq.query_ball({{0, 0, 0}, -1.0}), InvalidInput);
  EXPECT_THROW(lq.query_ball({{0, 0, 0}, nan}), InvalidInput);
  EXPECT_THROW(query_method_from_string("fast"), InvalidInput);
  try {
    lq.query_ball({{0, 0, 0}, -1.0});
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("radius"), std::string::npos);
  }
}

TEST(BlockBounds, ContainEveryElementOfTheBlock) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  long checked = 0;
  double tightness = 0.0;
  for (int l = 0; l < 300; ++l) {
    const Lattice lat = test::random_lattice(rng, l, {8, false, false});
    const BlockBounds bb(lat, 2);
    const Counts c = lat.counts();
    for (int b = 0; b < 30; ++b) {
      auto pick = [&](std::int64_t n, std::int64_t* lo, std::int64_t* hi) {
        *lo = static_cast<std::int64_t>(u01(rng) * n);
        *hi = *lo + 1 + static_cast<std::int64_t>(u01(rng) * (n - *lo));
      };
      IndexBlock blk;
      pick(c.u, &blk.i0, &blk.i1);
      pick(c.v, &blk.j0, &blk.j1);
      pick(c.w, &blk.k0, &blk.k1);
      for (int n = 0; n < lat.node_count(); ++n) {
        const auto& t = lat.definition().nodes[n];
        const Ball bound = bb.bound(t.center, t.radius, blk).ball;
        double far = 0.0;
        for (std::int64_t k = blk.k0; k < blk.k1; ++k)
          for (std::int64_t j = blk.j0; j < blk.j1; ++j)
            for (std::int64_t i = blk.i0; i < blk.i1; ++i) {
              const Ball e = lat.ball({i, j, k, n});
              const double reach = glm::length(e.center - bound.center) + e.radius;
              far = std::max(far, reach);
              EXPECT_LE(reach, bound.radius * (1 + 1e-12) + 1e-12) << "lattice " << l;
              ++checked;
            }
        tightness = std::max(tightness, bound.radius / std::max(far, 1e-300));
      }
    }
    // The whole-lattice bound holds every ball and beam.
    const Ball all = bb.lattice_bound();
    lat.for_each_beam([&](std::int64_t, const BeamId&, const BeamGeometry& g) {
      EXPECT_LE(glm::length(g.start.center - all.center) + g.start.radius, all.radius * (1 + 1e-12));
      EXPECT_LE(glm::length(g.end.center - all.center) + g.end.radius, all.radius * (1 + 1e-12));
    });
  }
  EXPECT_GT(checked, 100000);
}

}  // namespace
}  // namespace steady
