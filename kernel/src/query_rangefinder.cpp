// The RangeFinder paths of the ball-interference query: O(uv) rows along W, the paper's O(u) slabs and
// O(1) bricks. Templates are evaluated with the lattice's own evaluator; RangeFinder sees the inflated
// query, the exact tests the caller's.
#include <algorithm>

#include "query_internal.hpp"

namespace steady::detail {

namespace {

IndexRange full(std::int64_t lo, std::int64_t hi_exclusive) { return {lo, hi_exclusive - 1}; }

// The distinct (dj, dk) of the patterns, with (0, 0) first: one row prefix each per j.
struct PrefixOffsets {
  std::vector<std::pair<int, int>> offsets;
  std::vector<int> of_pattern;
  explicit PrefixOffsets(const Lattice& lat) {
    offsets.emplace_back(0, 0);
    for (const BeamPattern& b : lat.definition().beams) {
      const std::pair<int, int> o(b.dj, b.dk);
      auto it = std::find(offsets.begin(), offsets.end(), o);
      if (it == offsets.end()) {
        offsets.push_back(o);
        it = offsets.end() - 1;
      }
      of_pattern.push_back(static_cast<int>(it - offsets.begin()));
    }
  }
};

}  // namespace

void visit_rows(const QueryState& q, Probe& probe) {
  const Lattice& lat = q.lattice;
  const Counts& c = lat.counts();
  const auto& patterns = lat.definition().beams;
  const RowMotion& W = q.plan.rows_w;
  const PrefixOffsets po(lat);
  std::vector<SimilarityTransform> prefix(po.offsets.size());
  IndexRanges ks;
  for (std::int64_t j = 0; j < c.v; ++j) {
    for (std::size_t o = 0; o < po.offsets.size(); ++o)
      prefix[o] = q.eval.row_prefix(j + po.offsets[o].first, po.offsets[o].second);
    for (std::int64_t i = 0; i < c.u; ++i) {
      // The row (i, j, *) of every node: template at k = 0.
      const SimilarityTransform g0 = prefix[0] * q.eval.u().at(i);
      for (int n = 0; n < lat.node_count(); ++n) {
        steady_row_ranges(W, RowTemplate::ball(q.eval.node_ball(g0, n)), full(0, c.w), probe.inflated, ks);
        for (const IndexRange& r : ks.ranges())
          for (std::int64_t k = r.lo; k <= r.hi; ++k)
            if (!probe.ball(i, j, k, n)) return;
      }
      for (int p = 0; p < static_cast<int>(patterns.size()); ++p) {
        const IndexBlock& s = q.pattern_starts[static_cast<std::size_t>(p)];
        if (i < s.i0 || i >= s.i1 || j < s.j0 || j >= s.j1) continue;
        const BeamPattern& b = patterns[static_cast<std::size_t>(p)];
        const SimilarityTransform g1 = prefix[static_cast<std::size_t>(po.of_pattern[static_cast<std::size_t>(p)])] *
                                       q.eval.u().at(i + b.di);
        const BeamGeometry t = q.eval.beam_from_nodes(q.eval.node_ball(g0, b.from), q.eval.node_ball(g1, b.to), p);
        steady_row_ranges(W, RowTemplate::beam(t.start, t.end), full(s.k0, s.k1), probe.inflated, ks);
        for (const IndexRange& r : ks.ranges())
          for (std::int64_t k = r.lo; k <= r.hi; ++k)
            if (!probe.beam(i, j, k, p)) return;
      }
    }
  }
}

void visit_slabs(const QueryState& q, Probe& probe) {
  const Lattice& lat = q.lattice;
  const Counts& c = lat.counts();
  const auto& patterns = lat.definition().beams;
  const RowMotion& V = q.plan.slabs_v;
  const RowMotion& W = q.plan.slabs_w;
  IndexRanges js, ks;
  // The (j, k) candidates of a template at (i, 0, 0): the product of its V- and W-ranges.
  auto product = [&](const RowTemplate& t, const IndexRange& j_rows, const IndexRange& k_rows, auto&& test) {
    steady_row_ranges(V, t, j_rows, probe.inflated, js);
    if (js.empty()) return true;
    steady_row_ranges(W, t, k_rows, probe.inflated, ks);
    for (const IndexRange& rj : js.ranges())
      for (std::int64_t j = rj.lo; j <= rj.hi; ++j)
        for (const IndexRange& rk : ks.ranges())
          for (std::int64_t k = rk.lo; k <= rk.hi; ++k)
            if (!test(j, k)) return false;
    return true;
  };
  for (std::int64_t i = 0; i < c.u; ++i) {
    const SimilarityTransform g0 = q.eval.group(i, 0, 0);
    for (int n = 0; n < lat.node_count(); ++n) {
      const RowTemplate t = RowTemplate::ball(q.eval.node_ball(g0, n));
      if (!product(t, full(0, c.v), full(0, c.w), [&](std::int64_t j, std::int64_t k) { return probe.ball(i, j, k, n); }))
        return;
    }
    for (int p = 0; p < static_cast<int>(patterns.size()); ++p) {
      const IndexBlock& s = q.pattern_starts[static_cast<std::size_t>(p)];
      if (i < s.i0 || i >= s.i1) continue;
      const BeamPattern& b = patterns[static_cast<std::size_t>(p)];
      const BeamGeometry g = q.eval.beam_from_nodes(q.eval.node_ball(g0, b.from),
                                                    q.eval.node_ball(i + b.di, b.dj, b.dk, b.to), p);
      if (!product(RowTemplate::beam(g.start, g.end), full(s.j0, s.j1), full(s.k0, s.k1),
                   [&](std::int64_t j, std::int64_t k) { return probe.beam(i, j, k, p); }))
        return;
    }
  }
}

void visit_constant(const QueryState& q, Probe& probe) {
  const Lattice& lat = q.lattice;
  const Counts& c = lat.counts();
  const auto& patterns = lat.definition().beams;
  const QueryPlan& plan = q.plan;
  IndexRanges is, js, ks;
  // The candidates of one kind: the i-range of the template at (0,0,0), then the j- and k-ranges of the
  // same template, or of the template at (i,0,0) for each candidate i.
  auto candidates = [&](const RowTemplate& t0, auto&& slab_template, const IndexBlock& rows, auto&& test) {
    steady_row_ranges(plan.constant_u, t0, full(rows.i0, rows.i1), probe.inflated, is);
    if (is.empty()) return true;
    const RowMotion& V = plan.constant_per_slab ? plan.slabs_v : plan.constant_v;
    const RowMotion& W = plan.constant_per_slab ? plan.slabs_w : plan.constant_w;
    for (const IndexRange& ri : is.ranges())
      for (std::int64_t i = ri.lo; i <= ri.hi; ++i) {
        if (plan.constant_per_slab || i == ri.lo) {
          const RowTemplate t = plan.constant_per_slab ? slab_template(i) : t0;
          steady_row_ranges(V, t, full(rows.j0, rows.j1), probe.inflated, js);
          steady_row_ranges(W, t, full(rows.k0, rows.k1), probe.inflated, ks);
        }
        for (const IndexRange& rk : ks.ranges())
          for (std::int64_t k = rk.lo; k <= rk.hi; ++k)
            for (const IndexRange& rj : js.ranges())
              for (std::int64_t j = rj.lo; j <= rj.hi; ++j)
                if (!test(i, j, k)) return false;
      }
    return true;
  };
  const IndexBlock all{0, c.u, 0, c.v, 0, c.w};
  for (int n = 0; n < lat.node_count(); ++n) {
    auto templ = [&](std::int64_t i) { return RowTemplate::ball(q.eval.node_ball(i, 0, 0, n)); };
    if (!candidates(templ(0), templ, all,
                    [&](std::int64_t i, std::int64_t j, std::int64_t k) { return probe.ball(i, j, k, n); }))
      return;
  }
  for (int p = 0; p < static_cast<int>(patterns.size()); ++p) {
    const BeamPattern& b = patterns[static_cast<std::size_t>(p)];
    auto templ = [&](std::int64_t i) {
      const BeamGeometry g = q.eval.beam_from_nodes(q.eval.node_ball(i, 0, 0, b.from),
                                                    q.eval.node_ball(i + b.di, b.dj, b.dk, b.to), p);
      return RowTemplate::beam(g.start, g.end);
    };
    if (!candidates(templ(0), templ, q.pattern_starts[static_cast<std::size_t>(p)],
                    [&](std::int64_t i, std::int64_t j, std::int64_t k) { return probe.beam(i, j, k, p); }))
      return;
  }
}

}  // namespace steady::detail
