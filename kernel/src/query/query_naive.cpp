// The naive O(uvw) ball-interference query: the oracle of the tests and the baseline of the benchmarks.
// It is a fair baseline, not a slow one: each ball is evaluated once per query (a ring of k-slabs of ball
// geometry serves the beams that reach into the next slabs), and every ball and beam is exact-tested.
#include <algorithm>

#include "query/query_internal.hpp"
#include "steady/core/memory_budget.hpp"

namespace steady::detail {

void visit_naive(const QueryState& q, Probe& probe) {
  const Lattice& lat = q.lattice;
  const Counts& c = lat.counts();
  const int nodes = lat.node_count();
  const auto& patterns = lat.definition().beams;
  std::int64_t dk_lo = 0, dk_hi = 0;
  for (const BeamPattern& b : patterns) {
    dk_lo = std::min<std::int64_t>(dk_lo, b.dk);
    dk_hi = std::max<std::int64_t>(dk_hi, b.dk);
  }
  const std::int64_t ring = dk_hi - dk_lo + 1;
  const std::int64_t slab_size = c.u * c.v * nodes;
  require_memory(static_cast<std::uint64_t>(ring * slab_size) * sizeof(Ball), "the naive query's slab cache",
                 "use method 'auto' (blocks), which stores nothing per element");
  std::vector<Ball> cache(static_cast<std::size_t>(ring * slab_size));
  auto slot = [&](std::int64_t k) { return ((k % ring) + ring) % ring; };
  auto ball_at = [&](std::int64_t i, std::int64_t j, std::int64_t k, int n) -> const Ball& {
    return cache[static_cast<std::size_t>(slot(k) * slab_size + (j * c.u + i) * nodes + n)];
  };
  std::vector<SimilarityTransform> row(static_cast<std::size_t>(c.u));
  auto fill = [&](std::int64_t k) {
    Ball* out = &cache[static_cast<std::size_t>(slot(k) * slab_size)];
    for (std::int64_t j = 0; j < c.v; ++j) {
      lat.layout().row_transforms(j, k, row.data());  // any layout: this path is every layout's fallback
      for (const SimilarityTransform& g : row)
        for (int n = 0; n < nodes; ++n) *out++ = q.eval.node_ball(g, n);
    }
  };
  // Slabs k + dk_lo .. k + dk_hi must be in the ring while slab k is scanned; fill them in order.
  std::int64_t filled = std::max<std::int64_t>(0, dk_lo) - 1;
  for (std::int64_t k = 0; k < c.w; ++k) {
    for (std::int64_t f = std::max(filled + 1, k + dk_lo); f <= std::min(c.w - 1, k + dk_hi); ++f) fill(f);
    filled = std::max(filled, std::min(c.w - 1, k + dk_hi));
    for (std::int64_t j = 0; j < c.v; ++j)
      for (std::int64_t i = 0; i < c.u; ++i) {
        for (int n = 0; n < nodes; ++n)
          if (!probe.ball_geometry(ball_at(i, j, k, n), i, j, k, n)) return;
        for (int p = 0; p < static_cast<int>(patterns.size()); ++p) {
          const IndexBlock& s = q.pattern_starts[static_cast<std::size_t>(p)];
          if (i < s.i0 || i >= s.i1 || j < s.j0 || j >= s.j1 || k < s.k0 || k >= s.k1) continue;
          const BeamPattern& b = patterns[static_cast<std::size_t>(p)];
          const BeamGeometry g =
              q.eval.beam_from_nodes(ball_at(i, j, k, b.from), ball_at(i + b.di, j + b.dj, k + b.dk, b.to), p);
          if (!probe.beam_geometry(g, i, j, k, p)) return;
        }
      }
  }
}

}  // namespace steady::detail
