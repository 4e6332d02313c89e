// The RangeFinder paths of the ball-interference query: O(uv) rows along W, the paper's O(u) slabs and
// O(1) bricks. Templates are evaluated from the power tables; RangeFinder sees the inflated query, whose
// extents are computed once per query; each candidate is placed cheaply with the world-space powers and
// pre-checked before its exact geometry is evaluated and tested against the caller's ball.
#include <algorithm>

#include "query/query_internal.hpp"
#include "query/row_invariant.hpp"

namespace steady::detail {

namespace {

IndexRange full(std::int64_t lo, std::int64_t hi_exclusive) { return {lo, hi_exclusive - 1}; }

Ball moved(const SimilarityTransform& t, const Ball& b) { return t.apply(b); }

}  // namespace

// O(uv): every k-row (i, j, *) of every node and pattern. The node rows' templates and extents are
// computed once per query and row; a beam row's extent is combined from the extents of its two end
// nodes' rows (the end at k = dk is W'^dk of its row's template, so its extent is shifted by dk). A
// ring of node rows j + dj serves the beams that reach into the next rows.
void visit_rows(const QueryState& q, Probe& probe, bool reject) {
  const Lattice& lat = q.lattice;
  const Counts& c = lat.counts();
  const auto& patterns = lat.definition().beams;
  const RowMotion& W = q.plan.rows_w;
  const QueryExtents qe = query_extents(W, probe.inflated);
  const int nodes = lat.node_count();
  const ScratchLease scratch;
  IndexRanges& ks = scratch->ks;
  if (W.kind() == SimilarityKind::Identity) {
    // Every k-row is one repeated element: test its template (k = 0) exactly.
    for (std::int64_t j = 0; j < c.v; ++j)
      for (std::int64_t i = 0; i < c.u; ++i) {
        for (int n = 0; n < nodes; ++n) {
          steady_row_ranges(W, qe, RowTemplate::ball(q.eval.node_ball(i, j, 0, n)), full(0, c.w), ks);
          for (const IndexRange& r : ks.ranges())
            for (std::int64_t k = r.lo; k <= r.hi; ++k)
              if (!probe.ball(i, j, k, n)) return;
        }
        for (int p = 0; p < static_cast<int>(patterns.size()); ++p) {
          const IndexBlock& s = q.pattern_starts[static_cast<std::size_t>(p)];
          if (i < s.i0 || i >= s.i1 || j < s.j0 || j >= s.j1) continue;
          const BeamGeometry g = q.eval.beam(i, j, s.k0, p);
          steady_row_ranges(W, qe, RowTemplate::beam(g.start, g.end), full(s.k0, s.k1), ks);
          for (const IndexRange& r : ks.ranges())
            for (std::int64_t k = r.lo; k <= r.hi; ++k)
              if (!probe.beam(i, j, k, p)) return;
        }
      }
    return;
  }
  const auto& maps = W.maps();
  const std::size_t M = maps.size();
  std::int64_t dj_lo = 0, dj_hi = 0;
  for (const BeamPattern& b : patterns) {
    dj_lo = std::min<std::int64_t>(dj_lo, b.dj);
    dj_hi = std::max<std::int64_t>(dj_hi, b.dj);
  }
  const std::int64_t slots = dj_hi - dj_lo + 1;
  const std::size_t per_row = static_cast<std::size_t>(c.u * nodes);
  std::vector<Ball>& ring_balls = scratch->ring_balls;
  std::vector<Extent>& ring_extents = scratch->ring_extents;
  std::vector<char>& ring_ready = scratch->ring_ready;  // extents computed (lazily: rejected rows may not need them)
  ring_balls.resize(static_cast<std::size_t>(slots) * per_row);
  ring_extents.resize(static_cast<std::size_t>(slots) * per_row * M);
  ring_ready.assign(static_cast<std::size_t>(slots) * per_row, 0);
  const RowInvariant invariant(W, probe.inflated);
  auto extents = [&](std::size_t x) {
    Extent* e = &ring_extents[x * M];
    if (!ring_ready[x]) {
      for (std::size_t m = 0; m < M; ++m) e[m] = maps[m].extent(ring_balls[x]);
      ring_ready[x] = 1;
    }
    return e;
  };
  auto slot_of = [&](std::int64_t j) { return static_cast<std::size_t>(((j % slots) + slots) % slots); };
  auto at = [&](std::int64_t i, std::int64_t j, int n) { return slot_of(j) * per_row + static_cast<std::size_t>(i * nodes + n); };

  // Node rows of one j: templates, extents, candidates.
  auto node_row = [&](std::int64_t j) {
    const SimilarityTransform prefix = q.eval.row_prefix(j, 0);
    for (std::int64_t i = 0; i < c.u; ++i) {
      const double s0 = prefix.scale * q.u_scale(i);
      for (int n = 0; n < nodes; ++n) {
        const std::size_t x = at(i, j, n);
        Ball& b = ring_balls[x];
        b = {prefix.apply_point(q.u_node(i, n)), s0 * q.node_templates[static_cast<std::size_t>(n)].radius};
        ring_ready[x] = 0;
        if (reject && !invariant.may_meet(b)) continue;
        steady_row_ranges(W, qe, extents(x), full(0, c.w), ks);
        for (const IndexRange& r : ks.ranges())
          for (std::int64_t k = r.lo; k <= r.hi; ++k)
            if (!probe.ball_near(q.world_w.at(k).apply(b), i, j, k, n)) return false;
      }
    }
    return true;
  };

  std::vector<Extent> te(M), eb(M);
  std::int64_t computed = -1;
  for (std::int64_t j = 0; j < c.v; ++j) {
    for (std::int64_t jj = computed + 1; jj <= std::min(c.v - 1, j + dj_hi); ++jj)
      if (!node_row(jj)) return;
    computed = std::max(computed, std::min(c.v - 1, j + dj_hi));
    for (int p = 0; p < static_cast<int>(patterns.size()); ++p) {
      const IndexBlock& s = q.pattern_starts[static_cast<std::size_t>(p)];
      if (j < s.j0 || j >= s.j1) continue;
      const BeamPattern& bp = patterns[static_cast<std::size_t>(p)];
      const SimilarityTransform shift = q.world_w.at(bp.dk);
      for (std::int64_t i = s.i0; i < s.i1; ++i) {
        const std::size_t xa = at(i, j, bp.from), xb = at(i + bp.di, j + bp.dj, bp.to);
        const Ball& a = ring_balls[xa];
        const Ball b = shift.apply(ring_balls[xb]);
        if (reject && !invariant.may_meet(a, b)) continue;
        const Extent* ea = extents(xa);
        const Extent* ebn = extents(xb);
        for (std::size_t m = 0; m < M; ++m) {
          eb[m] = maps[m].shifted(ebn[m], static_cast<double>(bp.dk));
          te[m] = maps[m].combine(ea[m], eb[m], a, b);
        }
        steady_row_ranges(W, qe, te.data(), full(s.k0, s.k1), ks);
        for (const IndexRange& r : ks.ranges())
          for (std::int64_t k = r.lo; k <= r.hi; ++k) {
            const SimilarityTransform wk = q.world_w.at(k);
            if (!probe.beam_near(wk.apply(a), wk.apply(b), i, j, k, p)) return;
          }
      }
    }
  }
}

namespace {

// Tests the (j, k) candidates of one kind in slab i: elements W'^k V'^j of the slab's template.
template <class Test>
bool test_slab(const QueryState& q, const IndexRanges& js, const IndexRanges& ks, const Ball& a, const Ball* b,
               Test&& test) {
  for (const IndexRange& rj : js.ranges())
    for (std::int64_t j = rj.lo; j <= rj.hi; ++j) {
      const SimilarityTransform vj = q.world_v.at(j);
      const Ball va = moved(vj, a);
      const Ball vb = b ? moved(vj, *b) : va;
      for (const IndexRange& rk : ks.ranges())
        for (std::int64_t k = rk.lo; k <= rk.hi; ++k) {
          const SimilarityTransform wk = q.world_w.at(k);
          if (!test(j, k, moved(wk, va), moved(wk, vb))) return false;
        }
    }
  return true;
}

}  // namespace

void visit_slabs(const QueryState& q, Probe& probe, bool reject) {
  const Lattice& lat = q.lattice;
  const Counts& c = lat.counts();
  const auto& patterns = lat.definition().beams;
  const RowMotion& V = q.plan.slabs_v;
  const RowMotion& W = q.plan.slabs_w;
  const QueryExtents qv = query_extents(V, probe.inflated), qw = query_extents(W, probe.inflated);
  const std::vector<SimilarityTransform>& prefix = q.slab_prefixes;
  const ScratchLease scratch;
  GroupTemplates& t = scratch->templates;
  IndexRanges &js = scratch->js, &ks = scratch->ks;
  // The direction without a rotation map first: its range is cheaper and often empty.
  const bool w_first = W.rotates() && !V.rotates() ? false : !W.rotates();
  auto both = [&](const RowTemplate& t, const IndexRange& j_rows, const IndexRange& k_rows) {
    if (w_first) {
      steady_row_ranges(W, qw, t, k_rows, ks);
      if (ks.empty()) return false;
      steady_row_ranges(V, qv, t, j_rows, js);
      return !js.empty();
    }
    steady_row_ranges(V, qv, t, j_rows, js);
    if (js.empty()) return false;
    steady_row_ranges(W, qw, t, k_rows, ks);
    return !ks.empty();
  };
  // Slab rejection: a map of U that V and W leave unchanged takes on the whole slab i the values it
  // takes on the slab's template, so the query must overlap those.
  const std::vector<NormalizedMap>& slab_maps = q.plan.constant_u.maps();
  auto slab_may_meet = [&](const Ball& a, const Ball* b) {
    if (!reject) return true;
    Ball bound = a;
    if (b) {  // the beam lies in the ball about its axis midpoint reaching both balls
      bound.center = 0.5 * (a.center + b->center);
      bound.radius = 0.5 * glm::length(b->center - a.center) + std::max(a.radius, b->radius);
    }
    for (const NormalizedMap& m : slab_maps)
      if (!m.ranges_overlap(probe.inflated, bound)) return false;
    return true;
  };
  for (std::int64_t i = 0; i < c.u; ++i) {
    t.fill(q, prefix, i);
    for (int n = 0; n < lat.node_count(); ++n) {
      const Ball& tb = t.nodes[static_cast<std::size_t>(n)];
      if (!slab_may_meet(tb, nullptr)) continue;
      if (!both(RowTemplate::ball(tb), full(0, c.v), full(0, c.w))) continue;
      if (!test_slab(q, js, ks, tb, nullptr, [&](std::int64_t j, std::int64_t k, const Ball& e, const Ball&) {
            return probe.ball_near(e, i, j, k, n);
          }))
        return;
    }
    for (int p = 0; p < static_cast<int>(patterns.size()); ++p) {
      const IndexBlock& s = q.pattern_starts[static_cast<std::size_t>(p)];
      if (i < s.i0 || i >= s.i1) continue;
      const Ball& a = t.beam_start[static_cast<std::size_t>(p)];
      const Ball& b = t.beam_end[static_cast<std::size_t>(p)];
      if (!slab_may_meet(a, &b)) continue;
      if (!both(RowTemplate::beam(a, b), full(s.j0, s.j1), full(s.k0, s.k1))) continue;
      if (!test_slab(q, js, ks, a, &b, [&](std::int64_t j, std::int64_t k, const Ball& ea, const Ball& eb) {
            return probe.beam_near(ea, eb, i, j, k, p);
          }))
        return;
    }
  }
}

void visit_constant(const QueryState& q, Probe& probe) {
  const Lattice& lat = q.lattice;
  const Counts& c = lat.counts();
  const auto& patterns = lat.definition().beams;
  const QueryPlan& plan = q.plan;
  const RowMotion& V = plan.constant_per_slab ? plan.slabs_v : plan.constant_v;
  const RowMotion& W = plan.constant_per_slab ? plan.slabs_w : plan.constant_w;
  const QueryExtents qu = query_extents(plan.constant_u, probe.inflated);
  const QueryExtents qv = query_extents(V, probe.inflated), qw = query_extents(W, probe.inflated);
  const std::vector<SimilarityTransform>& prefix = q.slab_prefixes;
  const GroupTemplates& t0 = q.first_templates;
  const ScratchLease scratch;
  GroupTemplates& ti = scratch->templates;
  IndexRanges &is = scratch->is, &js = scratch->js, &ks = scratch->ks;
  // One kind: the i-range of its template at (0,0,0); then per candidate i the j- and k-ranges of the
  // same template (the paper's O(1)) or of the slab's template at (i,0,0), and the elements
  // W'^k V'^j of the slab's template U'^i T0 (or of T_i).
  // The template extents at (0,0,0) are fixed for the lattice (QueryState::constant_extents).
  auto kind = [&](const Ball& a0, const Ball* b0, std::size_t slot, const IndexBlock& rows, auto&& slab_template,
                  auto&& test) {
    const QueryState::TemplateExtents& te = q.constant_extents[slot];
    steady_row_ranges(plan.constant_u, qu, te.u.data(), full(rows.i0, rows.i1), is);
    if (is.empty()) return true;
    if (!plan.constant_per_slab) {
      steady_row_ranges(V, qv, te.v.data(), full(rows.j0, rows.j1), js);
      if (js.empty()) return true;
      steady_row_ranges(W, qw, te.w.data(), full(rows.k0, rows.k1), ks);
    }
    for (const IndexRange& ri : is.ranges())
      for (std::int64_t i = ri.lo; i <= ri.hi; ++i) {
        Ball a, b;
        if (plan.constant_per_slab) {
          slab_template(i, a, b);
          const RowTemplate r = b0 ? RowTemplate::beam(a, b) : RowTemplate::ball(a);
          steady_row_ranges(V, qv, r, full(rows.j0, rows.j1), js);
          if (js.empty()) continue;
          steady_row_ranges(W, qw, r, full(rows.k0, rows.k1), ks);
        } else {
          const SimilarityTransform ui = q.world_u.at(i);
          a = moved(ui, a0);
          if (b0) b = moved(ui, *b0);
        }
        if (!test_slab(q, js, ks, a, b0 ? &b : nullptr,
                       [&](std::int64_t j, std::int64_t k, const Ball& ea, const Ball& eb) { return test(i, j, k, ea, eb); }))
          return false;
      }
    return true;
  };
  for (int n = 0; n < lat.node_count(); ++n) {
    const Ball& a0 = t0.nodes[static_cast<std::size_t>(n)];
    if (!kind(a0, nullptr, static_cast<std::size_t>(n), IndexBlock{0, c.u, 0, c.v, 0, c.w},
              [&](std::int64_t i, Ball& a, Ball&) {
                ti.fill(q, prefix, i);
                a = ti.nodes[static_cast<std::size_t>(n)];
              },
              [&](std::int64_t i, std::int64_t j, std::int64_t k, const Ball& e, const Ball&) {
                return probe.ball_near(e, i, j, k, n);
              }))
      return;
  }
  for (int p = 0; p < static_cast<int>(patterns.size()); ++p) {
    const Ball& a0 = t0.beam_start[static_cast<std::size_t>(p)];
    const Ball& b0 = t0.beam_end[static_cast<std::size_t>(p)];
    if (!kind(a0, &b0, static_cast<std::size_t>(lat.node_count() + p), q.pattern_starts[static_cast<std::size_t>(p)],
              [&](std::int64_t i, Ball& a, Ball& b) {
                ti.fill(q, prefix, i);
                a = ti.beam_start[static_cast<std::size_t>(p)];
                b = ti.beam_end[static_cast<std::size_t>(p)];
              },
              [&](std::int64_t i, std::int64_t j, std::int64_t k, const Ball& ea, const Ball& eb) {
                return probe.beam_near(ea, eb, i, j, k, p);
              }))
      return;
  }
}

}  // namespace steady::detail
