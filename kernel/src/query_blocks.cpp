// The hierarchical ball-interference query (beyond the papers): index blocks of the lattice are bounded
// in closed form (block_bounds.hpp) and split only where the query may be, down to leaves of a few
// groups whose elements are exact-tested after a per-node and per-pattern bound test. Nothing is stored:
// the hierarchy is implicit in the index box and every bound is computed when visited.
#include <algorithm>

#include "query_internal.hpp"

namespace steady::detail {

namespace {

// Leaves hold at most this many groups: below it a split costs about as much (two bounds) as testing
// the groups' per-node and per-pattern bounds directly (measured on the benchmark lattices).
constexpr std::int64_t kLeafGroups = 8;

}  // namespace

void visit_blocks(const QueryState& q, Probe& probe) {
  const Lattice& lat = q.lattice;
  const Counts& c = lat.counts();
  const auto& patterns = lat.definition().beams;
  const Ball& query = probe.inflated;
  const Ball& templ = q.bounds.template_bound();
  thread_local std::vector<IndexBlock> stack;
  const IndexBlock lattice_block{0, c.u, 0, c.v, 0, c.w};
  auto misses = [&](const Ball& b) { return distance_to_ball(query.center, b) > query.radius; };

  auto leaf = [&](const IndexBlock& b) {
    for (int n = 0; n < lat.node_count(); ++n) {
      const Ball& t = q.node_templates[static_cast<std::size_t>(n)];
      if (misses(q.bounds.bound(t.center, t.radius, b).ball)) continue;
      for (std::int64_t k = b.k0; k < b.k1; ++k)
        for (std::int64_t j = b.j0; j < b.j1; ++j) {
          const SimilarityTransform prefix = q.eval.row_prefix(j, k);
          for (std::int64_t i = b.i0; i < b.i1; ++i)
            if (!probe.ball_in_group(prefix * q.eval.u().at(i), i, j, k, n)) return false;
        }
    }
    for (int p = 0; p < static_cast<int>(patterns.size()); ++p) {
      const IndexBlock s = intersect(b, q.pattern_starts[static_cast<std::size_t>(p)]);
      if (s.empty()) continue;
      const BeamPattern& bp = patterns[static_cast<std::size_t>(p)];
      const Ball& ts = q.beam_start_templates[static_cast<std::size_t>(p)];
      const Ball& te = q.beam_end_templates[static_cast<std::size_t>(p)];
      const Ball bs = q.bounds.bound(ts.center, ts.radius, s).ball;
      const Ball be = q.bounds.bound(te.center, te.radius, s.shifted(bp.di, bp.dj, bp.dk)).ball;
      if (distance_to_hull(query.center, bs, be) > query.radius) continue;
      for (std::int64_t k = s.k0; k < s.k1; ++k)
        for (std::int64_t j = s.j0; j < s.j1; ++j)
          for (std::int64_t i = s.i0; i < s.i1; ++i)
            if (!probe.beam(i, j, k, p)) return false;
    }
    return true;
  };

  stack.clear();
  stack.push_back(lattice_block);
  while (!stack.empty()) {
    const IndexBlock b = stack.back();
    stack.pop_back();
    // Everything attached to the block's groups: its balls, and its beams, which end in the block
    // extended by the patterns' offsets. All lie in the images of the template's bounding ball.
    const IndexBlock ext = intersect(
        IndexBlock{b.i0 + q.reach[0][0], b.i1 + q.reach[0][1], b.j0 + q.reach[1][0], b.j1 + q.reach[1][1],
                   b.k0 + q.reach[2][0], b.k1 + q.reach[2][1]},
        lattice_block);
    const BlockBound whole = q.bounds.bound(templ.center, templ.radius, ext);
    if (misses(whole.ball)) continue;
    if (b.groups() <= kLeafGroups) {
      if (!leaf(b)) return;
      continue;
    }
    // Split the block along the index direction that spreads it most in space.
    const std::int64_t len[3] = {b.i1 - b.i0, b.j1 - b.j0, b.k1 - b.k0};
    int axis = -1;
    for (int a = 0; a < 3; ++a)
      if (len[a] > 1 && (axis < 0 || whole.spread[a] > whole.spread[axis])) axis = a;
    IndexBlock lo = b, hi = b;
    if (axis == 0) lo.i1 = hi.i0 = b.i0 + len[0] / 2;
    if (axis == 1) lo.j1 = hi.j0 = b.j0 + len[1] / 2;
    if (axis == 2) lo.k1 = hi.k0 = b.k0 + len[2] / 2;
    stack.push_back(hi);
    stack.push_back(lo);
  }
}

}  // namespace steady::detail
