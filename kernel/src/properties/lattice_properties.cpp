#include "steady/properties/lattice_properties.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "steady/query/hub_overlaps.hpp"
#include "steady/properties/hub_union.hpp"
#include "steady/core/errors.hpp"
#include "steady/lattice/hub.hpp"
#include "steady/properties/similar_copies.hpp"
#include "properties/lattice_sums.hpp"

namespace steady {
namespace {

using namespace detail;

// ---- balls ------------------------------------------------------------------------------------------

MassMoments ball_sum(const Context& c) {
  const Counts& n = c.counts;
  MassMoments total;
  for (int node = 0; node < static_cast<int>(c.def.nodes.size()); ++node) {
    const TemplateNode& t = c.def.nodes[node];
    const MassMoments one = shifted(ball_moments(t.radius), t.center - c.P);
    const MassMoments row = sum_of_copies(c.U, c.P, one, n.u);
    const MassMoments slab = sum_of_copies(c.V, c.P, row, n.v);
    total += sum_of_copies(c.W, c.P, slab, n.w);
  }
  return total;
}

// ---- beams ------------------------------------------------------------------------------------------

MassMoments pattern_sum(const Context& c, int p) {
  if (c.absent[p]) return {};
  const BeamPattern& b = c.def.beams[p];
  const Counts& n = c.counts;
  const IndexBlock starts = pattern_start_groups(n, b);
    const IndexRange ri = range_i(starts), rj = range_j(starts), rk = range_k(starts);
  if (ri.size() == 0 || rj.size() == 0 || rk.size() == 0) return {};
  const SimilarityTransform w_dk = c.w_pow(b.dk);
  MassMoments slab;  // the pattern's beams of the virtual slab k = 0 (neighbours at k = dk)
  if (c.i_steady(b)) {
    const SimilarityTransform end = c.group(b.di, b.dj, b.dk);
    const MassMoments one = beam_moments(c, SimilarityTransform{}, end, p);
    slab = sum_of_copies(c.V, c.P, sum_of_copies(c.U, c.P, one, ri.size(), ri.lo), rj.size(), rj.lo);
  } else if (c.j_steady(b)) {
    // one row (j = 0) of distinct shapes, then its similar copies along j
    const SimilarityTransform head = w_dk * c.v_pow(b.dj);
    std::vector<MassMoments> row(ri.size());
    tbb::parallel_for(std::int64_t(0), ri.size(), [&](std::int64_t k) {
      c.progress->advance();
      const std::int64_t i = ri.lo + k;
      row[k] = beam_moments(c, c.u_pow(i),
                            head * c.u_pow(i + b.di), p);
    });
    MassMoments sum;
    for (const MassMoments& m : row) sum += m;
    slab = sum_of_copies(c.V, c.P, sum, rj.size(), rj.lo);
  } else {
    std::vector<SimilarityTransform> u_powers(n.u);
    for (std::int64_t i = 0; i < n.u; ++i) u_powers[i] = c.u_pow(i);
    std::vector<MassMoments> rows(rj.size());
    tbb::parallel_for(std::int64_t(0), rj.size(), [&](std::int64_t r) {
      c.progress->advance(ri.size());
      const std::int64_t j = rj.lo + r;
      const SimilarityTransform vj = c.v_pow(j);
      const SimilarityTransform head = w_dk * c.v_pow(j + b.dj);
      MassMoments sum;
      for (std::int64_t i = ri.lo; i < ri.hi; ++i) sum += beam_moments(c, vj * u_powers[i], head * u_powers[i + b.di], p);
      rows[r] = sum;
    });
    for (const MassMoments& m : rows) slab += m;
  }
  return sum_of_copies(c.W, c.P, slab, rk.size(), rk.lo);
}

// ---- hub overlap corrections ------------------------------------------------------------------------

MassMoments correction_about_P(const Context& c, const HubShape& h) {
  ++c.hub_shapes;
  const MassMoments corr = hub_overlap_correction(h, c.hub_options);
  if (corr.volume == 0.0 && corr.area == 0.0) return {};
  ++c.overlapping;
  return shifted(corr, h.center - c.P);
}

MassMoments class_sum(const Similarity& step, const Vec3& P, const MassMoments& m, const IndexClass& cls) {
  return sum_of_copies(step, P, m, cls.count, cls.first);
}

MassMoments hub_corrections(const Context& c) {
  const Counts& n = c.counts;
  MassMoments total;
  for (int node = 0; node < static_cast<int>(c.def.nodes.size()); ++node) {
    const std::vector<Incidence> all = incidences(c, node);
    if (all.size() < 2) continue;  // a lone stump overlaps nothing
    bool i_steady = true, j_steady = true;
    int reach_i = 0, reach_j = 0, reach_k = 0;
    for (const Incidence& s : all) {
      const BeamPattern& b = c.def.beams[s.pattern];
      i_steady = i_steady && c.i_steady(b);
      j_steady = j_steady && c.j_steady(b);
      reach_i = std::max(reach_i, std::abs(s.di));
      reach_j = std::max(reach_j, std::abs(s.dj));
      reach_k = std::max(reach_k, std::abs(s.dk));
    }
    i_steady = i_steady && j_steady;
    // Every hub of this node is, up to a similarity, a subset of its full hub (all stumps, neighbours outside
    // the lattice included) at the same non-steady indices: when none of those has overlapping caps, every
    // correction of the node is zero and its classes need not be built.
    const std::int64_t full_count = (i_steady ? 1 : n.u) * (j_steady ? 1 : n.v);
    const bool may_overlap = tbb::parallel_reduce(
        tbb::blocked_range<std::int64_t>(0, full_count, 64), false,
        [&](const tbb::blocked_range<std::int64_t>& range, bool any) {
          for (std::int64_t q = range.begin(); q != range.end() && !any; ++q) {
            const std::int64_t i = i_steady ? 0 : q % n.u, j = j_steady ? 0 : q / (i_steady ? 1 : n.u);
            std::vector<SimilarityTransform> other;
            for (const Incidence& s : all)
              other.push_back(c.group(i_steady ? s.di : i + s.di, j_steady ? s.dj : j + s.dj, s.dk));
            SimilarityTransform base;
            if (!i_steady) base = c.u_pow(i);
            if (!j_steady) base = c.v_pow(j) * base;
            ++c.hub_shapes;
            any = any_stump_caps_overlap(hub_shape_at(c, node, base, all, other));
          }
          return any;
        },
        [](bool a, bool b) { return a || b; });
    if (!may_overlap) continue;
    const auto ci = index_classes(n.u, reach_i, i_steady), cj = index_classes(n.v, reach_j, j_steady),
               ck = index_classes(n.w, reach_k, true);
    // Every (i, j, k) class triple: its representative hub in the frame the sums start from. Streamed
    // (O(uv) triples when the hub is steady along neither i nor j), reduced in a fixed order.
    auto triple = [&](std::size_t a, std::size_t bb, std::size_t kk) -> MassMoments {
      c.progress->advance();
      const IndexClass &xi = ci[a], &xj = cj[bb], &xk = ck[kk];
      std::vector<Incidence> present;
      std::vector<SimilarityTransform> other;
      // Which stumps exist is decided at the class's first index (the interior has them all).
      for (const Incidence& s : all)
        if (in_lattice(xi.first, s.di, n.u) && in_lattice(xj.first, s.dj, n.v) && in_lattice(xk.first, s.dk, n.w))
          present.push_back(s);
      if (present.size() < 2) return {};
      // The representative's frame: what the remaining sums do not place.
      for (const Incidence& s : present) {
        SimilarityTransform t;
        if (i_steady) {
          t = c.group(s.di, s.dj, s.dk);
        } else if (j_steady) {
          t = c.group(xi.first + s.di, s.dj, s.dk);
        } else {
          t = c.group(xi.first + s.di, xj.first + s.dj, s.dk);
        }
        other.push_back(t);
      }
      SimilarityTransform base;
      if (!i_steady) base = c.u_pow(xi.first);
      if (!j_steady) base = c.v_pow(xj.first) * base;
      MassMoments m = correction_about_P(c, hub_shape_at(c, node, base, present, other));
      if (m.volume == 0.0 && m.area == 0.0) return {};
      if (i_steady) m = class_sum(c.U, c.P, m, xi);
      if (j_steady) m = class_sum(c.V, c.P, m, xj);
      return class_sum(c.W, c.P, m, xk);
    };
    const std::size_t rows = ci.size() * cj.size();
    total += tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, rows, 16), MassMoments{},
        [&](const tbb::blocked_range<std::size_t>& range, MassMoments sum) {
          for (std::size_t r = range.begin(); r != range.end(); ++r)
            for (std::size_t kk = 0; kk < ck.size(); ++kk) sum += triple(r / cj.size(), r % cj.size(), kk);
          return sum;
        },
        [](const MassMoments& x, const MassMoments& y) { return x + y; });
  }
  return total;
}

// ---- omitted nodes ----------------------------------------------------------------------------------

MassMoments omission_corrections(const Context& c) {
  const auto& omitted = c.def.omitted;
  if (omitted.empty()) return {};
  MassMoments total;
  // balls
  std::set<std::tuple<std::int64_t, std::int64_t, std::int64_t, int>> gone;
  for (const NodeId& id : omitted) gone.insert({id.i, id.j, id.k, id.n});
  for (const auto& [i, j, k, node] : gone) {
    const TemplateNode& t = c.def.nodes[node];
    total -= transformed(shifted(ball_moments(t.radius), t.center - c.P), c.about_P(c.group(i, j, k)));
  }
  // beams killed by them, each once; and the hubs around them
  std::set<std::tuple<std::int64_t, std::int64_t, std::int64_t, int>> killed;
  std::set<std::tuple<std::int64_t, std::int64_t, std::int64_t, int>> touched(gone.begin(), gone.end());
  const Counts& n = c.counts;
  for (const auto& [i, j, k, node] : gone) {
    for (const Incidence& s : incidences(c, node)) {
      if (!in_lattice(i, s.di, n.u) || !in_lattice(j, s.dj, n.v) || !in_lattice(k, s.dk, n.w)) continue;
      const BeamPattern& b = c.def.beams[s.pattern];
      if (s.at_start) {
        killed.insert({i, j, k, s.pattern});
      } else {
        killed.insert({i - b.di, j - b.dj, k - b.dk, s.pattern});
      }
      touched.insert({i + s.di, j + s.dj, k + s.dk, s.at_start ? b.to : b.from});
    }
  }
  for (const auto& [i, j, k, p] : killed) {
    const BeamPattern& b = c.def.beams[p];
    total -= beam_moments(c, c.group(i, j, k), c.group(i + b.di, j + b.dj, k + b.dk), p);
  }
  for (const auto& [i, j, k, node] : touched) {
    const NodeId id{i, j, k, node};
    const MassMoments generic = correction_about_P(c, actual_hub(c, id, true));
    const MassMoments actual = c.lattice.node_exists(id) ? correction_about_P(c, actual_hub(c, id, false)) : MassMoments{};
    total += actual - generic;
  }
  return total;
}

LatticeProperties finish(const Context& c, const MassMoments& pre) {
  // From pre-placement moments about P to world moments about G(P): only G's linear part acts.
  const Similarity& G = c.G;
  SimilarityTransform linear = G.transform();
  linear.translation = Vec3(0.0);
  LatticeProperties out = properties_from_moments(transformed(pre, linear), G.apply_point(c.P));
  if (!is_finite(out.moments) || !(out.volume > 0.0))
    throw ResourceLimit("lattice properties: the moments overflow double precision (the lattice spans too many "
                        "orders of magnitude of scale)");
  out.beam_shapes = c.beam_shapes;
  out.hub_shapes = c.hub_shapes;
  out.overlapping_hub_shapes = c.overlapping;
  return out;
}

// The reference the moments are taken about: node 0 of the middle group (the sums' P, placed).
Vec3 reference_point(const Lattice& lattice) {
  const Counts& n = lattice.counts();
  return lattice.group_transform(n.u / 2, n.v / 2, n.w / 2).apply_point(lattice.definition().nodes[0].center);
}

// The sums over rows and slabs on the steady-brick view (the brick lattice: a re-indexing of the same
// groups), or, for a layout that is not a steady brick, every hub integrated on its own.
LatticeProperties closed_form_or_per_hub(const Lattice& lattice, const LatticePropertiesOptions& options,
                                         Progress& progress) {
  const Lattice* brick = lattice.brick_lattice();
  if (!brick) {
    progress.set_total(1);
    LatticeProperties out = lattice_properties_brute_force(lattice, options);
    progress.advance();
    return out;
  }
  Context c(*brick);
  c.hub_options = options.hub;
  c.progress = &progress;
  // Work units: beams of the rows enumerated, hub classes (an estimate; only the bar's pace depends on it).
  const Counts& n = c.counts;
  std::int64_t work = 1;
  for (const BeamPattern& b : c.def.beams) work += c.i_steady(b) ? 0 : c.j_steady(b) ? n.u : n.u * n.v;
  work += static_cast<std::int64_t>(c.def.nodes.size()) * 9 * n.u;
  progress.set_total(work);
  MassMoments total = ball_sum(c);
  for (int p = 0; p < brick->pattern_count(); ++p) total += pattern_sum(c, p);
  total += hub_corrections(c);
  total += omission_corrections(c);
  return finish(c, total);
}

}  // namespace

LatticeProperties properties_from_moments(const MassMoments& m, const Vec3& reference) {
  LatticeProperties out;
  out.moments = m;
  out.reference = reference;
  out.volume = m.volume;
  out.area = m.area;
  out.centroid = reference + centroid(m);
  out.inertia = central_inertia(m);
  return out;
}

namespace {
// Every node omitted leaves no ball: a volume of 0 that the centroid and the inertia would be divided by (the
// moments' overflow check caught it with a message about precision).
void require_some_ball(const Lattice& lattice) {
  if (lattice.ball_count() == 0)
    fail_input("omitted", "lists every node of the lattice: it has no ball or beam, so no volume, area, centroid or "
                          "inertia; omit fewer nodes");
}
}  // namespace

LatticeProperties lattice_properties(const Lattice& lattice, const LatticePropertiesOptions& options,
                                     Progress& progress) {
  require_some_ball(lattice);
  bool verified = false;
  HubOverlapReport report;
  if (options.check_clean) {
    // Every pair is needed for the union; more pairs than the union's limit can hold is refused below anyway.
    report = check_hub_overlaps(lattice, options.union_overlaps ? kMaxUnionHubs * 16 : 10, progress);
    if (report.overlap_count > 0 && !options.union_overlaps)
      fail_input("lattice", "not clean, " + report.describe() +
                                ". Its properties are not the sum of its hubs': thin the beams or nodes, or space the "
                                "groups further apart");
    if (report.overlap_count > static_cast<std::int64_t>(report.overlaps.size()))
      throw ResourceLimit("lattice: not clean, " + std::to_string(report.overlap_count) +
                          " pairs of hubs overlap, too many for their exact union (" + report.describe() +
                          "): thin the beams or nodes, or space the groups further apart");
    verified = report.verified;
  }
  progress.check();
  LatticeProperties out = closed_form_or_per_hub(lattice, options, progress);
  out.clean_verified = verified;
  if (report.overlap_count > 0) {
    progress.check();
    // (no progress of its own: it would reset the bar's total; clusters are few and small)
    const HubUnionCorrection u = hub_union_correction(lattice, report.overlaps, out.reference, options.hub);
    const LatticeProperties sums = out;
    out = properties_from_moments(out.moments + u.moments, out.reference);
    out.clean_verified = verified;
    out.beam_shapes = sums.beam_shapes;
    out.hub_shapes = sums.hub_shapes;
    out.overlapping_hub_shapes = sums.overlapping_hub_shapes;
    out.overlap_count = report.overlap_count;
    out.moved_cuts = u.moved_cuts;
    out.union_clusters = u.clusters;
    out.union_hubs = u.hubs;
    out.union_error = u.volume_error;
    out.overlap_description = report.describe();
  }
  progress.finish();
  return out;
}

LatticeProperties lattice_properties_brute_force(const Lattice& lattice, const LatticePropertiesOptions& options) {
  require_some_ball(lattice);
  const Vec3 reference = reference_point(lattice);
  std::atomic<std::int64_t> overlapping{0};
  Progress* const caller = current_progress();
  const MassMoments total = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::int64_t>(0, lattice.ball_count(), 256), MassMoments{},
      [&](const tbb::blocked_range<std::int64_t>& range, MassMoments sum) {
        const ProgressScope scope(caller);  // every hub integrated: minutes on a large lattice, so cancellable
        poll_progress();
        for (std::int64_t index = range.begin(); index != range.end(); ++index) {
          const Hub h = hub(lattice, lattice.ball_id(index));
          const HubProperties p = hub_properties(hub_shape(h), options.hub);
          overlapping += !p.closed_form;
          sum += shifted(p.moments, h.ball.center - reference);
        }
        return sum;
      },
      [](const MassMoments& x, const MassMoments& y) { return x + y; });
  LatticeProperties out = properties_from_moments(total, reference);
  out.hub_shapes = lattice.ball_count();
  out.overlapping_hub_shapes = overlapping;
  return out;
}

}  // namespace steady
