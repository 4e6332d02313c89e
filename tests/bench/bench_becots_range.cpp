// Issue 15's target for the BeCOTS RangeFinder: ball-interference queries on a 1000 x 1000 BeCOTS pattern at least
// 10^4 times faster than naive, and 0 misses against brute force over 10^5 random queries. One thread.
//   naive (lazy)      every group's similarity evaluated and every ball tested: what a lattice that stores nothing
//                     per element costs without a range finder;
//   naive (stored)    every ball evaluated once beforehand (2 x 10^6 balls, 64 MB), then tested per query;
//   RangeFinder       candidate groups from the log-polar bounds, then their balls tested exactly.
// The misses are counted on a 100 x 100 pattern of the same map (10^5 queries against all its balls).
// Then the same on BeCOTS lattices (balls and beams, becots_lattice): BecotsLatticeQuery against LatticeQuery's
// naive path and its automatic one (the general block path), 0 differences over 10^5 queries on 100 x 100 groups,
// and the times on a 1000 x 1000 triangle-mesh slab (10^6 balls, 3 x 10^6 beams). Last, stacks (6.3): a kagome
// stack of 100 x 100 groups in 64 layers offset along the normal and joined between layers, where only the layers
// whose shell of cones meets a query are searched (the O(1) stack query): 0 differences from naive on a smaller
// stack, the layers searched per query, and the times per query and per point against the general block path.
#include <cstdio>
#include <random>
#include <vector>

#include "bench_common.hpp"
#include "steady/cots/becots_lattice.hpp"
#include "steady/cots/becots_range.hpp"
#include "steady/query/becots_query.hpp"

using namespace steady;

namespace {

std::vector<Ball> queries_near(const BecotsMap& map, double spacing, int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> param(0.0, 1.0), unit(-1.0, 1.0);
  std::vector<Ball> out;
  for (int q = 0; q < count; ++q)
    out.push_back({map.map(param(rng), param(rng)) + Vec3(unit(rng), unit(rng), unit(rng)) * spacing,
                   spacing * (0.2 + 1.8 * param(rng))});
  return out;
}

BecotsRangeFinder pattern(const BecotsMap& map, int n) {
  const double step = 1.0 / (n - 1);
  const double spacing = glm::length(map.map(step, 0) - map.a());
  return BecotsRangeFinder(map, {{map.map(0.25 * step, 0.25 * step), 0.2 * spacing},
                                 {map.map(0.75 * step, 0.6 * step), 0.15 * spacing}},
                           n, n, step, step);
}

// Queries around the lattice's balls: up to two ball spacings away, radii up to one spacing.
std::vector<Ball> queries_around(const Lattice& lattice, int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0), unit(-1.0, 1.0);
  std::vector<Ball> out;
  for (int q = 0; q < count; ++q) {
    const Ball e = lattice.ball(lattice.ball_id(static_cast<std::int64_t>(u01(rng) * lattice.ball_count())));
    out.push_back({e.center + Vec3(unit(rng), unit(rng), unit(rng)) * (10.0 * e.radius), 5.0 * e.radius * u01(rng)});
  }
  return out;
}

bool lattices(const BecotsMap& map, bool long_run) {
  bool ok = true;
  {
    const Lattice lattice = becots_lattice(map, becots_connectivity("triangle"), {100, 100, 1}, 0.0015, 0.0, 0.6);
    const LatticeQuery lq(lattice);
    const BecotsLatticeQuery fast(lattice, map);
    const int count = long_run ? 1000000 : 100000;
    long differ = 0, hits = 0;
    for (const Ball& q : queries_around(lattice, count, 3)) {
      const BallQueryResult a = fast.query_ball(q), b = lq.query_ball(q, QueryMethod::Naive);
      differ += a.balls != b.balls || a.beams != b.beams;
      hits += static_cast<long>(b.balls.size() + b.beams.size());
    }
    std::printf("100 x 100 triangle-mesh BeCOTS slab (%lld balls, %lld beams): %d queries, %ld elements hit, %ld "
                "queries differing from naive\n",
                static_cast<long long>(lattice.ball_count()), static_cast<long long>(lattice.beam_count()), count, hits,
                differ);
    ok = ok && differ == 0;
  }
  const Lattice lattice = becots_lattice(map, becots_connectivity("triangle"), {1000, 1000, 1}, 0.00015, 0.0, 0.6);
  const LatticeQuery lq(lattice);
  const BecotsLatticeQuery fast(lattice, map);
  const std::vector<Ball> queries = queries_around(lattice, 1000, 4);
  long fast_hits = 0, auto_hits = 0, naive_hits = 0;
  const double t_fast = bench::median_seconds(5, [&] {
    fast_hits = 0;
    for (const Ball& q : queries) fast_hits += static_cast<long>(fast.query_ball(q).balls.size());
  }) / queries.size();
  const double t_auto = bench::seconds_of([&] {
    for (const Ball& q : queries) auto_hits += static_cast<long>(lq.query_ball(q, QueryMethod::Blocks).balls.size());
  }) / queries.size();
  const int naive_count = long_run ? 20 : 5;
  long naive_fast_hits = 0;
  const double t_naive = bench::seconds_of([&] {
    for (int q = 0; q < naive_count; ++q)
      naive_hits += static_cast<long>(lq.query_ball(queries[q], QueryMethod::Naive).balls.size());
  }) / naive_count;
  for (int q = 0; q < naive_count; ++q) naive_fast_hits += static_cast<long>(fast.query_ball(queries[q]).balls.size());
  std::printf("1000 x 1000 triangle-mesh BeCOTS slab (%lld balls, %lld beams), seconds per query, 1 thread:\n",
              static_cast<long long>(lattice.ball_count()), static_cast<long long>(lattice.beam_count()));
  std::printf("  %-24s %12.3e  (%d queries)\n", "LatticeQuery naive", t_naive, naive_count);
  std::printf("  %-24s %12.3e  (%zu queries; the plan: %s)\n", "LatticeQuery blocks", t_auto, queries.size(),
              lq.plan().describe().c_str());
  std::printf("  %-24s %12.3e  (%zu queries)\n", "BecotsLatticeQuery", t_fast, queries.size());
  std::printf("  speed-up: %.0fx over naive, %.0fx over blocks; same balls hit: %s\n", t_naive / t_fast, t_auto / t_fast,
              fast_hits == auto_hits && naive_hits == naive_fast_hits ? "yes" : "NO");
  return ok && fast_hits == auto_hits && naive_hits == naive_fast_hits;
}

BecotsConnectivity joined_kagome() {
  BecotsConnectivity cells = becots_connectivity("kagome");
  for (int n = 0; n < 3; ++n) {
    BeamPattern b;
    b.from = n, b.dk = 1, b.to = n;
    cells.beams.push_back(b);
  }
  return cells;
}

bool stacks(const BecotsMap& map, bool long_run) {
  const double spacing = glm::length(map.map(0.01, 0.0) - map.a());  // a tile of 100 x 100
  const double radius = 0.08 * spacing, offset = 0.5 * spacing;
  long differ = 0;
  {
    const Lattice lattice = becots_lattice(map, joined_kagome(), {30, 30, 16}, radius, 0.0, 0.6, offset);
    const LatticeQuery lq(lattice);
    const int count = long_run ? 100000 : 10000;
    for (const Ball& q : queries_around(lattice, count, 5)) {
      const BallQueryResult a = lq.query_ball(q), b = lq.query_ball(q, QueryMethod::Naive);
      differ += a.balls != b.balls || a.beams != b.beams;
    }
    std::printf("30 x 30 x 16 kagome stack by normal offset (%lld balls, %lld beams): %d queries on auto (%s), %ld "
                "differing from naive\n",
                static_cast<long long>(lattice.ball_count()), static_cast<long long>(lattice.beam_count()), count,
                to_string(lq.plan().automatic), differ);
  }
  const Lattice lattice = becots_lattice(map, joined_kagome(), {100, 100, 64}, radius, 0.0, 0.6, offset);
  const LatticeQuery lq(lattice);
  const BecotsLatticeQuery fast(lattice, map);
  const std::vector<Ball> queries = queries_around(lattice, 1000, 6);
  std::vector<Ball> points;
  for (const Ball& q : queries_around(lattice, 10000, 7)) points.push_back({q.center, 0.0});
  long layers = 0, fast_hits = 0, block_hits = 0, naive_hits = 0, naive_fast_hits = 0;
  for (const Ball& q : queries) layers += static_cast<long>(fast.candidate_layers(q).size());
  const double t_fast = bench::median_seconds(5, [&] {
    fast_hits = 0;
    for (const Ball& q : queries) fast_hits += static_cast<long>(lq.query_ball(q).balls.size());
  }) / queries.size();
  const double t_blocks = bench::median_seconds(3, [&] {
    block_hits = 0;
    for (const Ball& q : queries) block_hits += static_cast<long>(lq.query_ball(q, QueryMethod::Blocks).balls.size());
  }) / queries.size();
  long inside_fast = 0, inside_blocks = 0;
  const double p_fast = bench::median_seconds(5, [&] {
    inside_fast = 0;
    for (const Ball& p : points) inside_fast += lq.touches(p);
  }) / points.size();
  const double p_blocks = bench::median_seconds(3, [&] {
    inside_blocks = 0;
    for (const Ball& p : points) inside_blocks += lq.touches(p, QueryMethod::Blocks);
  }) / points.size();
  const int naive_count = long_run ? 10 : 3;
  const double t_naive = bench::seconds_of([&] {
    for (int q = 0; q < naive_count; ++q)
      naive_hits += static_cast<long>(lq.query_ball(queries[q], QueryMethod::Naive).balls.size());
  }) / naive_count;
  for (int q = 0; q < naive_count; ++q) naive_fast_hits += static_cast<long>(lq.query_ball(queries[q]).balls.size());
  std::printf("100 x 100 x 64 kagome stack by normal offset (%lld balls, %lld beams), 1 thread; auto is %s:\n",
              static_cast<long long>(lattice.ball_count()), static_cast<long long>(lattice.beam_count()),
              to_string(lq.plan().automatic));
  std::printf("  layers searched per query: %.2f of 64\n", static_cast<double>(layers) / queries.size());
  std::printf("  %-28s %12.3e s per query (%d queries)\n", "ball query, naive", t_naive, naive_count);
  std::printf("  %-28s %12.3e s per query (%zu queries)\n", "ball query, blocks", t_blocks, queries.size());
  std::printf("  %-28s %12.3e s per query\n", "ball query, becots (auto)", t_fast);
  std::printf("  %-28s %12.3e s per point (%zu points, %ld inside)\n", "point membership, blocks", p_blocks,
              points.size(), inside_blocks);
  std::printf("  %-28s %12.3e s per point\n", "point membership, becots", p_fast);
  std::printf("  speed-up: queries %.0fx over naive, %.1fx over blocks; points %.1fx over blocks; same hits: %s\n",
              t_naive / t_fast, t_blocks / t_fast, p_blocks / p_fast,
              fast_hits == block_hits && naive_hits == naive_fast_hits && inside_fast == inside_blocks ? "yes" : "NO");
  return differ == 0 && fast_hits == block_hits && naive_hits == naive_fast_hits && inside_fast == inside_blocks;
}

}  // namespace

int main(int argc, char** argv) {
  const bool long_run = bench::long_run(argc, argv);
  const BecotsMap map = BecotsMap({0, 0, 0}, {0.1, 1, 0}, {1.3, 1.2, 0}, {1, 0, 0}).bent(0.7);

  // Misses: brute force over every ball of a 100 x 100 pattern.
  {
    const int n = 100, count = long_run ? 1000000 : 100000;
    const BecotsRangeFinder finder = pattern(map, n);
    const double spacing = glm::length(map.map(1.0 / (n - 1), 0) - map.a());
    const std::vector<Ball> queries = queries_near(map, spacing, count, 1);
    long misses = 0, extra = 0, hits = 0;
    for (const Ball& q : queries) {
      const auto fast = finder.interfering(q), naive = finder.interfering_naive(q);
      hits += static_cast<long>(naive.size());
      misses += fast.size() < naive.size() ? static_cast<long>(naive.size() - fast.size()) : 0;
      extra += fast.size() > naive.size() ? static_cast<long>(fast.size() - naive.size()) : 0;
    }
    std::printf("100 x 100 pattern (%d balls): %d queries, %ld balls hit, %ld missed, %ld extra\n", 2 * n * n, count,
                hits, misses, extra);
  }

  // Speed on 1000 x 1000 groups.
  const int n = 1000;
  const BecotsRangeFinder finder = pattern(map, n);
  const double spacing = glm::length(map.map(1.0 / (n - 1), 0) - map.a());
  const std::vector<Ball> queries = queries_near(map, spacing, 1000, 2);
  long fast_hits = 0;
  const double fast = bench::median_seconds(5, [&] {
    fast_hits = 0;
    for (const Ball& q : queries) fast_hits += static_cast<long>(finder.interfering(q).size());
  }) / queries.size();
  const int naive_count = long_run ? 20 : 5;
  long lazy_hits = 0, lazy_fast_hits = 0;
  const double lazy = bench::seconds_of([&] {
    for (int q = 0; q < naive_count; ++q) lazy_hits += static_cast<long>(finder.interfering_naive(queries[q]).size());
  }) / naive_count;
  for (int q = 0; q < naive_count; ++q) lazy_fast_hits += static_cast<long>(finder.interfering(queries[q]).size());
  std::vector<Ball> stored;
  stored.reserve(2 * static_cast<std::size_t>(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      for (int b = 0; b < 2; ++b) stored.push_back(finder.ball(i, j, b));
  long stored_hits = 0;
  const int stored_count = long_run ? 1000 : 100;
  const double stored_time = bench::seconds_of([&] {
    for (int q = 0; q < stored_count; ++q)
      for (const Ball& b : stored)
        stored_hits += glm::length(b.center - queries[q].center) <= b.radius + queries[q].radius;
  }) / stored_count;
  long stored_fast_hits = 0;
  for (int q = 0; q < stored_count; ++q) stored_fast_hits += static_cast<long>(finder.interfering(queries[q]).size());
  std::printf("1000 x 1000 pattern (2 x 10^6 balls), seconds per query, 1 thread:\n");
  std::printf("  %-18s %12.3e  (%d queries, %ld hits)\n", "naive (lazy)", lazy, naive_count, lazy_hits);
  std::printf("  %-18s %12.3e  (%d queries, %ld hits; %.0f MB stored)\n", "naive (stored)", stored_time, stored_count,
              stored_hits, stored.size() * sizeof(Ball) / 1e6);
  std::printf("  %-18s %12.3e  (%zu queries, %ld hits)\n", "RangeFinder", fast, queries.size(), fast_hits);
  std::printf("  speed-up: %.0fx over naive (lazy), %.0fx over naive (stored); same hits: %s\n", lazy / fast,
              stored_time / fast, lazy_hits == lazy_fast_hits && stored_hits == stored_fast_hits ? "yes" : "NO");
  const bool patterns_ok = lazy_hits == lazy_fast_hits && stored_hits == stored_fast_hits;
  const bool lattices_ok = lattices(map, long_run);
  return patterns_ok && lattices_ok && stacks(map, long_run) ? 0 : 1;
}
