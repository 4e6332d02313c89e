#include "steady/lattice/lattice.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "lattice/rank.hpp"
#include "steady/lattice/any_order_layout.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/progress.hpp"
#include "steady/core/numeric_range.hpp"

namespace steady {
namespace {

// Element counts must stay exact in int64 arithmetic with room for products: 2^62.
constexpr double kMaxElements = 4.6e18;

std::string field(const char* name, std::size_t index) {
  std::ostringstream os;
  os << name << "[" << index << "]";
  return os.str();
}

std::int64_t permuted_index(const AxisOrder& axes, int b, std::int64_t i, std::int64_t j, std::int64_t k) {
  const std::int64_t index[3] = {i, j, k};
  return index[axes[static_cast<std::size_t>(b)]];
}

// The template in brick axes: beam offsets and omitted nodes permuted (brick axis b is lattice axis axes[b]).
LatticeDefinition in_brick_axes(const LatticeDefinition& d, const SteadyBrick& view) {
  LatticeDefinition b;
  b.nodes = d.nodes;
  b.layout = view.layout_in_brick_axes;
  for (BeamPattern p : d.beams) {
    const int di = p.di, dj = p.dj, dk = p.dk;
    p.di = static_cast<int>(permuted_index(view.axes, 0, di, dj, dk));
    p.dj = static_cast<int>(permuted_index(view.axes, 1, di, dj, dk));
    p.dk = static_cast<int>(permuted_index(view.axes, 2, di, dj, dk));
    b.beams.push_back(p);
  }
  for (const NodeId& id : d.omitted)
    b.omitted.push_back({permuted_index(view.axes, 0, id.i, id.j, id.k), permuted_index(view.axes, 1, id.i, id.j, id.k),
                         permuted_index(view.axes, 2, id.i, id.j, id.k), id.n});
  return b;
}

}  // namespace

IndexBlock pattern_start_groups(const Counts& counts, const BeamPattern& b) {
  // Start indices x with 0 <= x < count and 0 <= x + offset < count, per direction.
  auto range = [](std::int64_t count, int offset, std::int64_t* lo, std::int64_t* hi) {
    *lo = std::max<std::int64_t>(0, -offset);
    *hi = std::max(*lo, std::min<std::int64_t>(count, count - offset));
  };
  IndexBlock r;
  range(counts.u, b.di, &r.i0, &r.i1);
  range(counts.v, b.dj, &r.j0, &r.j1);
  range(counts.w, b.dk, &r.k0, &r.k1);
  return r;
}

Lattice::Lattice(LatticeDefinition definition) : def_(std::move(definition)) {
  validate();
  build_indexing();
  const SteadyBrick* view = def_.layout->steady_brick();
  if (view && view->reordered()) brick_ = std::make_shared<const Lattice>(in_brick_axes(def_, *view));
}

Lattice Lattice::incremental(std::vector<TemplateNode> nodes, std::vector<BeamPattern> beams, Counts counts,
                             const Similarity& U, const Similarity& V, const Similarity& W, const Similarity& G) {
  return Lattice({std::move(nodes), std::move(beams), SteadyBrickLayout::steps(counts, U, V, W, G), {}});
}

Lattice Lattice::interpolating(std::vector<TemplateNode> nodes, std::vector<BeamPattern> beams, Counts counts,
                               const Similarity& U_total, const Similarity& V_total, const Similarity& W_total,
                               const Similarity& G) {
  auto layout = SteadyBrickLayout::make(counts, {U_total, StepControl::Cumulative}, {V_total, StepControl::Cumulative},
                                        {W_total, StepControl::Cumulative}, G);
  return Lattice({std::move(nodes), std::move(beams), std::move(layout), {}});
}

Lattice Lattice::from_frames(std::vector<TemplateNode> nodes, std::vector<BeamPattern> beams, Counts counts,
                             const Frame& base, const Frame& end_u, const Frame& end_v, const Frame& end_w) {
  validate_frame(base, "base");
  validate_frame(end_u, "end_u");
  validate_frame(end_v, "end_v");
  validate_frame(end_w, "end_w");
  const Similarity G = Similarity::from_frame(base);
  const SimilarityTransform to_local = G.inverse().transform();
  // The cumulative similarity of a direction, in the template's coordinates: G o X' = frame(end).
  auto local_total = [&](const Frame& end) {
    return Similarity::from_transform(to_local * Similarity::from_frame(end).transform());
  };
  return interpolating(std::move(nodes), std::move(beams), counts, local_total(end_u), local_total(end_v),
                       local_total(end_w), G);
}

Lattice Lattice::ordered(std::vector<TemplateNode> nodes, std::vector<BeamPattern> beams, Counts counts,
                         const DirectionControl& U, const DirectionControl& V, const DirectionControl& W,
                         const Similarity& G, const AxisOrder& order, std::vector<NodeId> omitted) {
  LayoutPtr layout = order == kUVW ? LayoutPtr(SteadyBrickLayout::make(counts, U, V, W, G))
                                   : AnyOrderLayout::make(counts, U, V, W, G, order);
  return Lattice({std::move(nodes), std::move(beams), std::move(layout), std::move(omitted)});
}

Lattice Lattice::with_layout(LayoutPtr layout) const {
  LatticeDefinition d = def_;
  d.layout = std::move(layout);
  return Lattice(std::move(d));
}

void Lattice::validate() const {
  const auto& d = def_;
  if (!d.layout) fail_input("layout", "the lattice needs a layout");
  if (d.nodes.empty()) fail_input("nodes", "the template needs at least one node");
  for (std::size_t n = 0; n < d.nodes.size(); ++n) {
    const std::string f = field("nodes", n);
    require_within(d.nodes[n].center, kMaxCoordinate, f + ".center");
    require_positive(d.nodes[n].radius, f + ".radius");
    require_within(d.nodes[n].radius, kMaxCoordinate, f + ".radius");
  }
  const Counts& counts = d.layout->counts();  // >= 1 each: the layout checked them
  const std::int64_t cs[3] = {counts.u, counts.v, counts.w};
  const double total = static_cast<double>(cs[0]) * cs[1] * cs[2] * static_cast<double>(d.nodes.size()) *
                       std::max<double>(1.0, static_cast<double>(d.beams.size()));
  if (total > kMaxElements) fail_input("counts", "the lattice has more elements than 64-bit indices can address");

  const int nn = static_cast<int>(d.nodes.size());
  for (std::size_t p = 0; p < d.beams.size(); ++p) {
    const BeamPattern& b = d.beams[p];
    const std::string f = field("beams", p);
    if (b.from < 0 || b.from >= nn)
      fail_input(f + ".from", "node " + std::to_string(b.from) + " does not exist (the template has " +
                                  std::to_string(nn) + " nodes)");
    if (b.to < 0 || b.to >= nn)
      fail_input(f + ".to", "node " + std::to_string(b.to) + " does not exist (the template has " +
                                std::to_string(nn) + " nodes)");
    const bool same_group = b.di == 0 && b.dj == 0 && b.dk == 0;
    if (same_group && b.from == b.to) fail_input(f, "joins a node to itself");
    if (same_group && d.nodes[b.from].center == d.nodes[b.to].center)
      fail_input(f, "joins two nodes with the same center (a beam of length zero)");
    if (b.from_radius.has_value() != b.to_radius.has_value())
      fail_input(f + ".radii", "give both end radii or neither");
    if (b.has_radii()) {
      require_positive(*b.from_radius, f + ".radii[0]");
      require_positive(*b.to_radius, f + ".radii[1]");
      // A beam end thicker than its node would stick out of it: the hull would not be ball plus stumps.
      if (*b.from_radius > d.nodes[b.from].radius)
        fail_input(f + ".radii[0]", "must not exceed the radius of node " + std::to_string(b.from) + " (" +
                                        std::to_string(d.nodes[b.from].radius) + ")");
      if (*b.to_radius > d.nodes[b.to].radius)
        fail_input(f + ".radii[1]", "must not exceed the radius of node " + std::to_string(b.to) + " (" +
                                        std::to_string(d.nodes[b.to].radius) + ")");
    }
    for (std::size_t q = 0; q < p; ++q) {
      const BeamPattern& o = d.beams[q];
      const bool same = o.from == b.from && o.to == b.to && o.di == b.di && o.dj == b.dj && o.dk == b.dk;
      const bool reversed = o.from == b.to && o.to == b.from && o.di == -b.di && o.dj == -b.dj && o.dk == -b.dk;
      if (same || reversed) fail_input(f, "describes the same beams as " + field("beams", q));
    }
  }
  for (std::size_t q = 0; q < d.omitted.size(); ++q) {
    const NodeId& id = d.omitted[q];
    if (id.i < 0 || id.i >= cs[0] || id.j < 0 || id.j >= cs[1] || id.k < 0 || id.k >= cs[2] || id.n < 0 ||
        id.n >= nn)
      fail_input(field("omitted", q), "names a node outside the lattice");
  }
}

std::int64_t Lattice::node_linear(const NodeId& id) const {
  const Counts& c = counts();
  return ((id.k * c.v + id.j) * c.u + id.i) * node_count() + id.n;
}

NodeId Lattice::node_from_linear(std::int64_t linear) const {
  NodeId id;
  const std::int64_t nn = node_count();
  id.n = static_cast<int>(linear % nn);
  std::int64_t g = linear / nn;
  const Counts& c = counts();
  id.i = g % c.u;
  g /= c.u;
  id.j = g % c.v;
  id.k = g / c.v;
  return id;
}

void Lattice::build_indexing() {
  omitted_linear_.clear();
  for (const NodeId& id : def_.omitted) omitted_linear_.push_back(node_linear(id));
  std::sort(omitted_linear_.begin(), omitted_linear_.end());
  omitted_linear_.erase(std::unique(omitted_linear_.begin(), omitted_linear_.end()), omitted_linear_.end());
  ball_count_ = counts().groups() * node_count() -
                static_cast<std::int64_t>(omitted_linear_.size());

  const int np = pattern_count();
  pattern_ranges_.assign(np, PatternRange{});
  killed_beams_.assign(np, {});
  pattern_offsets_.assign(np + 1, 0);
  for (int p = 0; p < np; ++p) {
    const BeamPattern& b = def_.beams[p];
    PatternRange& r = pattern_ranges_[p];
    const IndexBlock starts = pattern_start_groups(counts(), b);
    r = {starts.i0, starts.i1, starts.j0, starts.j1, starts.k0, starts.k1};
    auto in_range = [&r](std::int64_t i, std::int64_t j, std::int64_t k) {
      return i >= r.i0 && i < r.i1 && j >= r.j0 && j < r.j1 && k >= r.k0 && k < r.k1;
    };
    std::vector<std::int64_t>& killed = killed_beams_[p];
    for (std::int64_t linear : omitted_linear_) {
      const NodeId id = node_from_linear(linear);
      if (id.n == b.from && in_range(id.i, id.j, id.k)) killed.push_back(r.local(id.i, id.j, id.k));
      if (id.n == b.to && in_range(id.i - b.di, id.j - b.dj, id.k - b.dk))
        killed.push_back(r.local(id.i - b.di, id.j - b.dj, id.k - b.dk));
    }
    std::sort(killed.begin(), killed.end());
    killed.erase(std::unique(killed.begin(), killed.end()), killed.end());
    pattern_offsets_[p + 1] = pattern_offsets_[p] + r.size() - static_cast<std::int64_t>(killed.size());
  }
  beam_count_ = pattern_offsets_[np];
}

bool Lattice::group_exists(std::int64_t i, std::int64_t j, std::int64_t k) const {
  return def_.layout->contains(i, j, k);
}

SimilarityTransform Lattice::group_transform(std::int64_t i, std::int64_t j, std::int64_t k) const {
  return def_.layout->group_transform(i, j, k);
}

Similarity Lattice::group_similarity(std::int64_t i, std::int64_t j, std::int64_t k) const {
  return def_.layout->group_similarity(i, j, k);
}

const Lattice* Lattice::brick_lattice() const {
  const SteadyBrick* view = def_.layout->steady_brick();
  if (!view) return nullptr;
  return view->reordered() ? brick_.get() : this;
}

NodeId Lattice::to_brick(const NodeId& id) const {
  const SteadyBrick* view = def_.layout->steady_brick();
  if (!view || !view->reordered()) return id;
  return {permuted_index(view->axes, 0, id.i, id.j, id.k), permuted_index(view->axes, 1, id.i, id.j, id.k),
          permuted_index(view->axes, 2, id.i, id.j, id.k), id.n};
}

NodeId Lattice::from_brick(const NodeId& id) const {
  const SteadyBrick* view = def_.layout->steady_brick();
  if (!view || !view->reordered()) return id;
  std::int64_t index[3];
  const std::int64_t brick[3] = {id.i, id.j, id.k};
  for (int b = 0; b < 3; ++b) index[view->axes[b]] = brick[b];
  return {index[0], index[1], index[2], id.n};
}

BeamId Lattice::to_brick(const BeamId& id) const {
  const NodeId n = to_brick(NodeId{id.i, id.j, id.k, 0});
  return {n.i, n.j, n.k, id.pattern};
}

BeamId Lattice::from_brick(const BeamId& id) const {
  const NodeId n = from_brick(NodeId{id.i, id.j, id.k, 0});
  return {n.i, n.j, n.k, id.pattern};
}

bool Lattice::node_exists(const NodeId& id) const {
  if (!group_exists(id.i, id.j, id.k) || id.n < 0 || id.n >= node_count()) return false;
  return !std::binary_search(omitted_linear_.begin(), omitted_linear_.end(), node_linear(id));
}

Ball Lattice::ball(const NodeId& id) const {
  if (id.n < 0 || id.n >= node_count()) fail_input("node", "index " + std::to_string(id.n) + " does not exist");
  const TemplateNode& t = def_.nodes[id.n];
  return group_transform(id.i, id.j, id.k).apply(Ball{t.center, t.radius});
}

NodeId Lattice::beam_start(const BeamId& id) const {
  return NodeId{id.i, id.j, id.k, def_.beams.at(id.pattern).from};
}

NodeId Lattice::beam_end(const BeamId& id) const {
  const BeamPattern& b = def_.beams.at(id.pattern);
  return NodeId{id.i + b.di, id.j + b.dj, id.k + b.dk, b.to};
}

bool Lattice::beam_exists(const BeamId& id) const { return beam_index(id) >= 0; }

BeamGeometry Lattice::beam(const BeamId& id) const {
  if (!beam_exists(id)) fail_input("beam", "does not exist");
  const BeamPattern& b = def_.beams[id.pattern];
  BeamGeometry g{ball(beam_start(id)), ball(beam_end(id))};
  if (b.has_radii()) {
    g.start.radius = *b.from_radius * g.start.radius / def_.nodes[b.from].radius;
    g.end.radius = *b.to_radius * g.end.radius / def_.nodes[b.to].radius;
  }
  return g;
}

std::int64_t Lattice::ball_index(const NodeId& id) const {
  if (!node_exists(id)) return -1;
  return detail::rank_excluding(omitted_linear_, node_linear(id));
}

NodeId Lattice::ball_id(std::int64_t index) const {
  if (index < 0 || index >= ball_count_)
    fail_input("ball index", std::to_string(index) + " is out of range [0, " + std::to_string(ball_count_) + ")");
  return node_from_linear(detail::unrank_excluding(omitted_linear_, index));
}

std::int64_t Lattice::beam_index(const BeamId& id) const {
  if (id.pattern < 0 || id.pattern >= pattern_count()) return -1;
  const PatternRange& r = pattern_ranges_[id.pattern];
  if (id.i < r.i0 || id.i >= r.i1 || id.j < r.j0 || id.j >= r.j1 || id.k < r.k0 || id.k >= r.k1) return -1;
  const auto& killed = killed_beams_[id.pattern];
  const std::int64_t local = r.local(id.i, id.j, id.k);
  if (std::binary_search(killed.begin(), killed.end(), local)) return -1;
  return pattern_offsets_[id.pattern] + detail::rank_excluding(killed, local);
}

BeamId Lattice::beam_id(std::int64_t index) const {
  if (index < 0 || index >= beam_count_)
    fail_input("beam index", std::to_string(index) + " is out of range [0, " + std::to_string(beam_count_) + ")");
  const int p = static_cast<int>(std::upper_bound(pattern_offsets_.begin(), pattern_offsets_.end(), index) -
                                 pattern_offsets_.begin()) - 1;
  const PatternRange& r = pattern_ranges_[p];
  const std::int64_t local = detail::unrank_excluding(killed_beams_[p], index - pattern_offsets_[p]);
  const std::int64_t ni = r.i1 - r.i0, nj = r.j1 - r.j0;
  BeamId id;
  id.pattern = p;
  id.i = r.i0 + local % ni;
  id.j = r.j0 + (local / ni) % nj;
  id.k = r.k0 + local / (ni * nj);
  return id;
}

std::uint64_t Lattice::listing_bytes() const {
  // balls: 3 doubles + radius; beams: two int64 indices + two radii
  return static_cast<std::uint64_t>(ball_count_) * 32u + static_cast<std::uint64_t>(beam_count_) * 32u;
}

void Lattice::balls(double* centers, double* radii) const {
  const Counts& c = counts();
  const int nn = node_count();
  // Listing 10^8 balls takes seconds: each row polls the caller's progress (Ctrl-C from Python).
  Progress* const caller = current_progress();
  // Tasks of (j, k) rows of groups, each with one buffer for its rows' group transforms; a row's first ball
  // index comes from the rank of its first node.
  auto list_rows = [&](const tbb::blocked_range<std::int64_t>& rows) {
    const ProgressScope scope(caller);
    std::vector<SimilarityTransform> groups(static_cast<std::size_t>(c.u));
    for (std::int64_t row = rows.begin(); row != rows.end(); ++row) {
      poll_progress();
      const std::int64_t j = row % c.v, k = row / c.v;
      def_.layout->row_transforms(j, k, groups.data());
      std::int64_t linear = node_linear(NodeId{0, j, k, 0});
      auto skip = std::lower_bound(omitted_linear_.begin(), omitted_linear_.end(), linear);
      std::int64_t index = linear - (skip - omitted_linear_.begin());
      for (const SimilarityTransform& s : groups)
        for (int n = 0; n < nn; ++n, ++linear) {
          if (skip != omitted_linear_.end() && *skip == linear) {
            ++skip;
            continue;
          }
          const Vec3 p = s.apply_point(def_.nodes[n].center);
          centers[3 * index + 0] = p.x;
          centers[3 * index + 1] = p.y;
          centers[3 * index + 2] = p.z;
          radii[index] = s.scale * def_.nodes[n].radius;
          ++index;
        }
    }
  };
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, c.v * c.w), list_rows);
}

void Lattice::beams(std::int64_t* start, std::int64_t* end, double* start_radius, double* end_radius) const {
  const Counts& c = counts();
  Progress* const caller = current_progress();  // polled per row, as in balls()
  for (int p = 0; p < pattern_count(); ++p) {
    const BeamPattern& b = def_.beams[p];
    const PatternRange& r = pattern_ranges_[p];
    const auto& killed = killed_beams_[p];
    const std::int64_t nj = r.j1 - r.j0, nk = r.k1 - r.k0;
    const double node_from = def_.nodes[b.from].radius, node_to = def_.nodes[b.to].radius;
    auto list_rows = [&](const tbb::blocked_range<std::int64_t>& rows) {
      // The group transforms of a row and of the row its beams end in (the radii as beam() gives them).
      const ProgressScope scope(caller);
      std::vector<SimilarityTransform> here(static_cast<std::size_t>(c.u)), there(static_cast<std::size_t>(c.u));
      for (std::int64_t row = rows.begin(); row != rows.end(); ++row) {
        poll_progress();
        const std::int64_t j = r.j0 + row % nj, k = r.k0 + row / nj;
        def_.layout->row_transforms(j, k, here.data());
        def_.layout->row_transforms(j + b.dj, k + b.dk, there.data());
        std::int64_t local = r.local(r.i0, j, k);
        auto skip = std::lower_bound(killed.begin(), killed.end(), local);
        std::int64_t index = pattern_offsets_[p] + local - (skip - killed.begin());
        for (std::int64_t i = r.i0; i < r.i1; ++i, ++local) {
          if (skip != killed.end() && *skip == local) {
            ++skip;
            continue;
          }
          start[index] = ball_index(NodeId{i, j, k, b.from});
          end[index] = ball_index(NodeId{i + b.di, j + b.dj, k + b.dk, b.to});
          const double ball_from = here[static_cast<std::size_t>(i)].scale * node_from;
          const double ball_to = there[static_cast<std::size_t>(i + b.di)].scale * node_to;
          start_radius[index] = b.has_radii() ? *b.from_radius * ball_from / node_from : ball_from;
          end_radius[index] = b.has_radii() ? *b.to_radius * ball_to / node_to : ball_to;
          ++index;
        }
      }
    };
    tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, nj * nk), list_rows);
  }
}

void Lattice::for_each_ball(const std::function<void(std::int64_t, const NodeId&, const Ball&)>& visit) const {
  for (std::int64_t index = 0; index < ball_count_; ++index) {
    const NodeId id = ball_id(index);
    visit(index, id, ball(id));
  }
}

void Lattice::for_each_beam(
    const std::function<void(std::int64_t, const BeamId&, const BeamGeometry&)>& visit) const {
  for (std::int64_t index = 0; index < beam_count_; ++index) {
    const BeamId id = beam_id(index);
    visit(index, id, beam(id));
  }
}

}  // namespace steady
