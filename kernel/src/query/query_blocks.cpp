// The hierarchical ball-interference query (beyond the papers): index blocks of the lattice are bounded
// in closed form (block_bounds.hpp) and split only where the query may be, down to leaves of a few
// groups whose elements are exact-tested. Nothing is stored: the hierarchy is implicit in the index box
// and every bound is computed when visited.
//
// A block is first tested with one ball holding everything attached to it (the template's bounding ball
// over the block extended by the patterns' offsets, which holds the beams' far ends). Small blocks then
// get the tight test, one bound per kind of element: each node's ball over the block, each pattern's
// beams in the hull of its start nodes' bound and its end nodes' bound (the block shifted by the
// offset); the kinds that pass are the only ones tested further down. Children are visited nearer
// first, so a query that only asks whether anything is hit stops early.
#include <algorithm>
#include <cstdint>

#include "query/query_internal.hpp"

namespace steady::detail {

namespace {

// Leaves hold at most this many groups: below it a split costs about as much (two bounds) as testing
// the groups' elements directly (measured on the benchmark lattices).
constexpr std::int64_t kLeafGroups = 8;
// Blocks of at most this many groups get the per-kind tight test (above it the union ball is tight
// enough relative to the block, and the per-kind bounds would cost more than they save).
constexpr std::int64_t kTightGroups = 64;
// The per-kind mask is a 64-bit word: lattices with more nodes plus patterns test every kind in leaves.
constexpr int kMaskKinds = 64;

using Entry = BlockEntry;

}  // namespace

void visit_blocks(const QueryState& q, Probe& probe) {
  const Lattice& lat = q.lattice;
  const Counts& c = lat.counts();
  const auto& patterns = lat.definition().beams;
  const int nodes = lat.node_count();
  const int kinds = nodes + static_cast<int>(patterns.size());
  const bool masked = kinds <= kMaskKinds;
  const Vec3& center = probe.inflated.center;
  const Ball& templ = q.bounds->template_bound();
  const IndexBlock lattice_block{0, c.u, 0, c.v, 0, c.w};
  // The query's radius shrinks to the sink's reach as a nearest-element search finds nearer elements.
  auto gap_to = [&](const Ball& b) { return distance_to_ball(center, b) - probe.pruning_radius(); };

  // Per-kind tight test: which kinds may meet the query within block b.
  auto kind_mask = [&](const IndexBlock& b) {
    std::uint64_t mask = 0;
    for (int n = 0; n < nodes; ++n) {
      const Ball& t = q.node_templates[static_cast<std::size_t>(n)];
      if (gap_to(q.bounds->bound(t.center, t.radius, b).ball) <= 0.0) mask |= std::uint64_t(1) << n;
    }
    for (int p = 0; p < static_cast<int>(patterns.size()); ++p) {
      const IndexBlock s = intersect(b, q.pattern_starts[static_cast<std::size_t>(p)]);
      if (s.empty()) continue;
      const BeamPattern& bp = patterns[static_cast<std::size_t>(p)];
      const Ball& ts = q.beam_start_templates[static_cast<std::size_t>(p)];
      const Ball& te = q.beam_end_templates[static_cast<std::size_t>(p)];
      const Ball bs = q.bounds->bound(ts.center, ts.radius, s).ball;
      const Ball be = q.bounds->bound(te.center, te.radius, s.shifted(bp.di, bp.dj, bp.dk)).ball;
      if (distance_to_hull(center, bs, be) <= probe.pruning_radius()) mask |= std::uint64_t(1) << (nodes + p);
    }
    return mask;
  };

  // Bounds a block; false when nothing attached to it can meet the query.
  auto evaluate = [&](const IndexBlock& b, std::uint64_t parent_kinds, Entry& e) {
    const IndexBlock ext = intersect(
        IndexBlock{b.i0 + q.reach[0][0], b.i1 + q.reach[0][1], b.j0 + q.reach[1][0], b.j1 + q.reach[1][1],
                   b.k0 + q.reach[2][0], b.k1 + q.reach[2][1]},
        lattice_block);
    const BlockBound whole = q.bounds->bound(templ.center, templ.radius, ext);
    e.block = b;
    e.distance = distance_to_ball(center, whole.ball);
    e.gap = e.distance - probe.pruning_radius();
    for (int a = 0; a < 3; ++a) e.spread[a] = whole.spread[a];
    e.kinds = parent_kinds;
    if (e.gap > 0.0) return false;
    if (masked && b.groups() <= kTightGroups) {
      e.kinds &= kind_mask(b);
      if (e.kinds == 0) return false;
    }
    return true;
  };

  auto leaf = [&](const IndexBlock& b, std::uint64_t mask) {
    for (int n = 0; n < nodes; ++n) {
      if (masked && !(mask >> n & 1)) continue;
      if (!masked) {
        const Ball& t = q.node_templates[static_cast<std::size_t>(n)];
        if (gap_to(q.bounds->bound(t.center, t.radius, b).ball) > 0.0) continue;
      }
      for (std::int64_t k = b.k0; k < b.k1; ++k)
        for (std::int64_t j = b.j0; j < b.j1; ++j) {
          const SimilarityTransform prefix = q.eval.row_prefix(j, k);
          for (std::int64_t i = b.i0; i < b.i1; ++i)
            if (!probe.ball_in_group(prefix * q.eval.u().at(i), i, j, k, n)) return false;
        }
    }
    for (int p = 0; p < static_cast<int>(patterns.size()); ++p) {
      if (masked && !(mask >> (nodes + p) & 1)) continue;
      const IndexBlock s = intersect(b, q.pattern_starts[static_cast<std::size_t>(p)]);
      if (s.empty()) continue;
      if (!masked) {
        const BeamPattern& bp = patterns[static_cast<std::size_t>(p)];
        const Ball& ts = q.beam_start_templates[static_cast<std::size_t>(p)];
        const Ball& te = q.beam_end_templates[static_cast<std::size_t>(p)];
        const Ball bs = q.bounds->bound(ts.center, ts.radius, s).ball;
        const Ball be = q.bounds->bound(te.center, te.radius, s.shifted(bp.di, bp.dj, bp.dk)).ball;
        if (distance_to_hull(center, bs, be) > probe.pruning_radius()) continue;
      }
      for (std::int64_t k = s.k0; k < s.k1; ++k)
        for (std::int64_t j = s.j0; j < s.j1; ++j)
          for (std::int64_t i = s.i0; i < s.i1; ++i)
            if (!probe.beam(i, j, k, p)) return false;
    }
    return true;
  };

  const ScratchLease scratch;
  std::vector<Entry>& stack = scratch->stack;
  stack.clear();
  Entry root;
  if (!evaluate(lattice_block, ~std::uint64_t(0), root)) return;
  stack.push_back(root);
  std::int64_t popped = 0;
  while (!stack.empty()) {
    if ((++popped & (kPollCandidates - 1)) == 0) poll_progress();  // blocks pruned without any candidate, too
    const Entry e = stack.back();
    stack.pop_back();
    const IndexBlock& b = e.block;
    if (e.distance > probe.pruning_radius()) continue;  // the sink's reach shrank since it was pushed
    if (b.groups() <= kLeafGroups) {
      if (!leaf(b, e.kinds)) return;
      continue;
    }
    // Split the block along the index direction that spreads it most in space.
    const std::int64_t len[3] = {b.i1 - b.i0, b.j1 - b.j0, b.k1 - b.k0};
    int axis = -1;
    for (int a = 0; a < 3; ++a)
      if (len[a] > 1 && (axis < 0 || e.spread[a] > e.spread[axis])) axis = a;
    IndexBlock lo = b, hi = b;
    if (axis == 0) lo.i1 = hi.i0 = b.i0 + len[0] / 2;
    if (axis == 1) lo.j1 = hi.j0 = b.j0 + len[1] / 2;
    if (axis == 2) lo.k1 = hi.k0 = b.k0 + len[2] / 2;
    Entry el, eh;
    const bool keep_lo = evaluate(lo, e.kinds, el), keep_hi = evaluate(hi, e.kinds, eh);
    // The nearer child on top of the stack.
    if (keep_lo && keep_hi) {
      if (el.gap <= eh.gap) {
        stack.push_back(eh);
        stack.push_back(el);
      } else {
        stack.push_back(el);
        stack.push_back(eh);
      }
    } else if (keep_lo) {
      stack.push_back(el);
    } else if (keep_hi) {
      stack.push_back(eh);
    }
  }
}

}  // namespace steady::detail
