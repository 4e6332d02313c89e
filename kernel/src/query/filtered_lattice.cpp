#include "steady/query/filtered_lattice.hpp"

#include <tbb/parallel_for.h>

#include "query/hit_sinks.hpp"

#include "steady/core/memory_budget.hpp"
#include "steady/core/progress.hpp"

namespace steady {

FilteredLattice::FilteredLattice(Lattice lattice, FilterPtr filter, QueryMethod method)
    : lattice_(std::make_unique<Lattice>(std::move(lattice))),
      query_(std::make_unique<LatticeQuery>(*lattice_)),
      filter_(std::move(filter)),
      method_(query_->resolve(method)),
      scale_(typical_element_size(*lattice_)) {}

bool FilteredLattice::keeps(const NodeId& id) const {
  const std::int64_t index = lattice_->ball_index(id);
  if (index < 0) return false;
  if (!filter_) return true;
  if (!mask_.empty()) return mask_[static_cast<std::size_t>(index)] != 0;
  const Ball b = lattice_->ball(id);
  std::uint8_t keep = 0;
  filter_->evaluate(*lattice_, &id, &b, 1, &keep);
  return keep != 0;
}

void FilteredLattice::materialize() {
  if (materialized() || !filter_) return;
  require_memory(static_cast<std::uint64_t>(lattice_->ball_count()),
                 "materialize(): a mask of the " + std::to_string(lattice_->ball_count()) + " balls (one byte each)",
                 "query the filtered lattice without materializing it (query_ball, contains, distance)");
  std::vector<std::uint8_t> m(static_cast<std::size_t>(lattice_->ball_count()));
  ball_mask(m.data());
  mask_ = std::move(m);
}

void FilteredLattice::ball_mask(std::uint8_t* out) const {
  const Lattice& lat = *lattice_;
  const std::int64_t n = lat.ball_count();
  if (!filter_) {
    std::fill(out, out + n, std::uint8_t(1));
    return;
  }
  if (!mask_.empty()) {
    std::copy(mask_.begin(), mask_.end(), out);
    return;
  }
  // One batch per (j, k) row of groups: its nodes' ids and balls, filtered together.
  const Counts& c = lat.counts();
  const int nodes = lat.node_count();
  Progress* const caller = current_progress();
  auto row = [&](std::int64_t r) {
    const ProgressScope scope(caller);  // a row may take long (a filter running queries): it can be cancelled
    poll_progress();
    const std::int64_t j = r % c.v, k = r / c.v;
    std::vector<NodeId> ids;
    std::vector<Ball> balls;
    std::vector<std::int64_t> index;
    ids.reserve(static_cast<std::size_t>(c.u * nodes));
    std::vector<SimilarityTransform> groups(static_cast<std::size_t>(c.u));
    lat.layout().row_transforms(j, k, groups.data());
    for (std::int64_t i = 0; i < c.u; ++i) {
      const SimilarityTransform& g = groups[static_cast<std::size_t>(i)];
      for (int node = 0; node < nodes; ++node) {
        const NodeId id{i, j, k, node};
        const std::int64_t x = lat.ball_index(id);
        if (x < 0) continue;
        ids.push_back(id);
        const TemplateNode& t = lat.definition().nodes[static_cast<std::size_t>(node)];
        balls.push_back(g.apply(Ball{t.center, t.radius}));
        index.push_back(x);
      }
    }
    std::vector<std::uint8_t> keep(ids.size());
    filter_->evaluate(lat, ids.data(), balls.data(), ids.size(), keep.data());
    for (std::size_t q = 0; q < ids.size(); ++q) out[index[q]] = keep[q];
  };
  if (filter_->parallel_safe())
    tbb::parallel_for(std::int64_t(0), c.v * c.w, row);
  else
    for (std::int64_t r = 0; r < c.v * c.w; ++r) row(r);
}

void FilteredLattice::beam_mask_from(const std::uint8_t* balls, std::uint8_t* out) const {
  const Lattice& lat = *lattice_;
  const Counts& c = lat.counts();
  const auto& patterns = lat.definition().beams;
  const std::int64_t nodes = lat.node_count();
  const bool dense = lat.definition().omitted.empty();
  Progress* const caller = current_progress();
  for (int p = 0; p < static_cast<int>(patterns.size()); ++p) {
    const BeamPattern& b = patterns[static_cast<std::size_t>(p)];
    tbb::parallel_for(std::int64_t(0), c.v * c.w, [&](std::int64_t r) {
      const ProgressScope scope(caller);
      poll_progress();
      const std::int64_t j = r % c.v, k = r / c.v;
      if (dense) {
        // Nothing omitted: a row's beams are consecutive, and ball indices are the linear node indices.
        const IndexBlock starts = pattern_start_groups(c, b);
        const std::int64_t i0 = starts.i0, i1 = starts.i1;
        if (i1 <= i0) return;
        const std::int64_t first = lat.beam_index(BeamId{i0, j, k, p});
        if (first < 0) return;
        const std::int64_t s0 = ((k * c.v + j) * c.u + i0) * nodes + b.from;
        const std::int64_t e0 = (((k + b.dk) * c.v + j + b.dj) * c.u + i0 + b.di) * nodes + b.to;
        for (std::int64_t i = 0; i < i1 - i0; ++i) out[first + i] = balls[s0 + i * nodes] && balls[e0 + i * nodes] ? 1 : 0;
        return;
      }
      for (std::int64_t i = 0; i < c.u; ++i) {
        const std::int64_t x = lat.beam_index(BeamId{i, j, k, p});
        if (x < 0) continue;
        const std::int64_t s = lat.ball_index(NodeId{i, j, k, b.from});
        const std::int64_t e = lat.ball_index(NodeId{i + b.di, j + b.dj, k + b.dk, b.to});
        out[x] = balls[s] && balls[e] ? 1 : 0;
      }
    });
  }
}

void FilteredLattice::beam_mask(std::uint8_t* out) const {
  if (!filter_) {
    std::fill(out, out + lattice_->beam_count(), std::uint8_t(1));
    return;
  }
  if (!mask_.empty()) {
    beam_mask_from(mask_.data(), out);
    return;
  }
  require_memory(static_cast<std::uint64_t>(lattice_->ball_count()),
                 "a mask of the " + std::to_string(lattice_->ball_count()) + " balls (one byte each)",
                 "query the filtered lattice without a mask (query_ball, contains, distance)");
  std::vector<std::uint8_t> balls(static_cast<std::size_t>(lattice_->ball_count()));
  ball_mask(balls.data());
  beam_mask_from(balls.data(), out);
}

namespace {
// Forwards the hits whose nodes the filtered lattice keeps.
struct FilterSink : HitSink {
  const FilteredLattice& fl;
  HitSink& inner;
  FilterSink(const FilteredLattice& f, HitSink& s) : fl(f), inner(s) {}
  bool on_hit(const ElementHit& h) override {
    if (h.is_beam) {
      const Lattice& lat = fl.lattice();
      if (!fl.keeps(lat.beam_start(BeamId{h.i, h.j, h.k, h.kind})) || !fl.keeps(lat.beam_end(BeamId{h.i, h.j, h.k, h.kind})))
        return true;
    } else if (!fl.keeps(NodeId{h.i, h.j, h.k, h.kind})) {
      return true;
    }
    return inner.on_hit(h);
  }
  double reach() const override { return inner.reach(); }
};
}  // namespace

void FilteredLattice::visit(const Ball& query, HitSink& sink) const { visit_with(query, sink, method_); }

void FilteredLattice::visit_nearest(const Ball& query, HitSink& sink) const {
  const bool blocks = method_ != QueryMethod::Naive && query_->plan().steady_reason.empty();
  visit_with(query, sink, blocks ? QueryMethod::Blocks : method_);
}

void FilteredLattice::visit_with(const Ball& query, HitSink& sink, QueryMethod method) const {
  if (!filter_) {
    query_->visit(query, sink, method);
    return;
  }
  FilterSink f(*this, sink);
  query_->visit(query, f, method);
}

BallQueryResult FilteredLattice::query_ball(const Ball& query) const {
  return detail::collect_hits(query, [&](HitSink& sink) { visit(query, sink); });
}

bool FilteredLattice::touches(const Ball& query) const {
  return detail::any_hit([&](HitSink& sink) { visit(query, sink); });
}

}  // namespace steady
