#include "steady/query/becots_query.hpp"

#include <algorithm>
#include <cmath>

#include "query/hit_sinks.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/progress.hpp"
#include "steady/query/interference.hpp"

namespace steady {
namespace {
// How far the lattice's steps may be from the map's per-tile similarities (relative to the map's size, as
// map_distance measures) and still count as laid on that map: far above rounding, far below any other map.
constexpr double kSameStepTolerance = 1e-9;

// Buckets of the polar table per layer: a layer's interval then covers a few buckets, and a point query reads one.
constexpr std::size_t kBucketsPerLayer = 4;
// The table's entries at most (layer ids over all buckets, beyond one per bucket), so that layers whose intervals
// are wide against their spacing cannot make it quadratic; fewer buckets are used then.
constexpr std::size_t kEntriesPerLayer = 64;

// Pieces a beam's bound is cut into, at most: a piece's ball is about as thick as the beam, so that a layer's
// shell of cones is not widened by balls around whole beams (a beam is as long as a tile, layers are closer).
constexpr int kMaxBeamPieces = 16;

// Balls holding the hull of two balls, one per piece of n equal pieces: the hull is the union of the balls
// interpolated between the two (centres and radii), and those of one piece lie in the ball around its midpoint.
void add_hull_bounds(const Ball& a, const Ball& b, std::vector<Ball>& out) {
  const double length = glm::length(b.center - a.center), thick = std::max(a.radius, b.radius);
  const int n = std::clamp(static_cast<int>(std::ceil(length / std::max(2.0 * thick, 1e-300))), 1, kMaxBeamPieces);
  for (int p = 0; p < n; ++p) {
    const double t0 = static_cast<double>(p) / n, t1 = static_cast<double>(p + 1) / n;
    const Vec3 c0 = a.center + t0 * (b.center - a.center), c1 = a.center + t1 * (b.center - a.center);
    const double r0 = a.radius + t0 * (b.radius - a.radius), r1 = a.radius + t1 * (b.radius - a.radius);
    out.push_back({0.5 * (c0 + c1), 0.5 * glm::length(c1 - c0) + std::max(r0, r1)});
  }
}

bool laid_in_becots_order(const SteadyBrick& brick, const Counts& counts) {
  // U and V commute, so only W's place matters: first (a stack), or nowhere (one layer).
  return brick.axes[0] == 2 || counts.w == 1;
}
}  // namespace

BecotsLatticeQuery::BecotsLatticeQuery(const Lattice& lattice, const BecotsMap& map) : lattice_(lattice) {
  const SteadyBrick* brick = lattice.layout().steady_brick();
  const Counts& counts = lattice.counts();
  const double du = 1.0 / static_cast<double>(counts.u), dv = 1.0 / static_cast<double>(counts.v);
  if (!brick || !laid_in_becots_order(*brick, counts) ||
      brick->step_along(0).map_distance(map.field(du, 0.0)) > kSameStepTolerance ||
      brick->step_along(1).map_distance(map.field(0.0, dv)) > kSameStepTolerance ||
      brick->placement.map_distance(Similarity::identity()) > kSameStepTolerance)
    fail_input("lattice", "is not a BeCOTS lattice of this map (lay it with becots_lattice)");
  const Similarity& W = brick->step_along(2);
  if (counts.w > 1 && W.kind() != SimilarityKind::Translation && W.kind() != SimilarityKind::Identity)
    fail_input("lattice", "its layers are not moved by a translation");
  // Layer k's bounding balls, in its group (0, 0, k): its nodes, and along each beam it starts, the far end placed
  // in its end group (i, j, k + dk) whether or not that group exists (a bound only). W is applied first, so the far
  // end is U^di V^dj W^(k + dk) of its node: W does not commute with the spirals, and a template raised as a whole
  // would put it off by (m - 1) k z.
  const auto& def = lattice.definition();
  for (std::int64_t k = 0; k < counts.w; ++k) {
    const Similarity raise = W.power(static_cast<double>(k));
    std::vector<Ball> layer;
    for (const TemplateNode& n : def.nodes) layer.push_back(raise.apply(Ball{n.center, n.radius}));
    for (const BeamPattern& b : def.beams) {
      const Similarity to_end = map.field(b.di * du, b.dj * dv) * W.power(static_cast<double>(k + b.dk));
      const TemplateNode& from = def.nodes[static_cast<std::size_t>(b.from)];
      const TemplateNode& to = def.nodes[static_cast<std::size_t>(b.to)];
      add_hull_bounds(raise.apply(Ball{from.center, from.radius}), to_end.apply(Ball{to.center, to.radius}), layer);
    }
    layers_.emplace_back(map, std::move(layer), static_cast<int>(counts.u), static_cast<int>(counts.v), du, dv);
  }
  // The polar table: the layers' intervals over buckets of the angle; fewer buckets when the intervals are wide.
  double lo = INFINITY, hi = -INFINITY;
  for (const BecotsRangeFinder& f : layers_) {
    const auto p = f.polar_interval();
    if (p.everything) return;  // a layer around the apex: every query searches every layer
    lo = std::min(lo, p.p0), hi = std::max(hi, p.p1);
  }
  std::size_t buckets = kBucketsPerLayer * layers_.size();
  for (;; buckets = std::max<std::size_t>(1, buckets / 2)) {
    polar_lo_ = lo;
    polar_step_ = std::max((hi - lo) / static_cast<double>(buckets), 1e-300);
    std::size_t entries = 0;
    for (const BecotsRangeFinder& f : layers_) {
      const auto p = f.polar_interval();
      entries += static_cast<std::size_t>(std::floor((p.p1 - lo) / polar_step_) - std::floor((p.p0 - lo) / polar_step_)) + 1;
    }
    if (entries <= buckets + kEntriesPerLayer * layers_.size() || buckets == 1) break;
  }
  buckets_.assign(buckets, {});
  for (std::size_t k = 0; k < layers_.size(); ++k) {
    const auto p = layers_[k].polar_interval();
    const auto b0 = static_cast<std::size_t>(std::clamp(std::floor((p.p0 - lo) / polar_step_), 0.0, double(buckets - 1)));
    const auto b1 = static_cast<std::size_t>(std::clamp(std::floor((p.p1 - lo) / polar_step_), 0.0, double(buckets - 1)));
    for (std::size_t b = b0; b <= b1; ++b) buckets_[b].push_back(static_cast<int>(k));
  }
}

std::vector<int> BecotsLatticeQuery::candidate_layers(const Ball& query) const {
  std::vector<int> out;
  const auto all = [&] {
    for (int k = 0; k < layer_count(); ++k) out.push_back(k);
    return out;
  };
  if (buckets_.empty() || layers_.empty()) return all();
  const auto q = layers_.front().polar_interval(query);  // the same angle for every layer: one apex and axis
  if (q.everything) return all();
  const double n = static_cast<double>(buckets_.size());
  const double f0 = std::floor((q.p0 - polar_lo_) / polar_step_), f1 = std::floor((q.p1 - polar_lo_) / polar_step_);
  if (f1 < 0.0 || f0 >= n) return out;  // misses every layer's shell
  const auto b0 = static_cast<std::size_t>(std::max(f0, 0.0)), b1 = static_cast<std::size_t>(std::min(f1, n - 1.0));
  for (std::size_t b = b0; b <= b1; ++b) out.insert(out.end(), buckets_[b].begin(), buckets_[b].end());
  if (b1 > b0) {
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }
  return out;
}

std::int64_t BecotsLatticeQuery::visit(const Ball& query, HitSink& sink) const {
  validate_query_ball(query, "query");
  const auto& def = lattice_.definition();
  const int nodes = static_cast<int>(def.nodes.size()), patterns = static_cast<int>(def.beams.size());
  std::int64_t tested = 0;
  for (const int k : candidate_layers(query)) {
    // Ranges of different turns may share groups when the lattice wraps around its axis: each group once.
    const std::vector<GroupRange> ranges = layers_[static_cast<std::size_t>(k)].candidates(query);
    for (std::size_t r = 0; r < ranges.size(); ++r)
      for (std::int64_t j = ranges[r].j0; j <= ranges[r].j1; ++j)
        for (std::int64_t i = ranges[r].i0; i <= ranges[r].i1; ++i) {
          bool again = false;
          for (std::size_t e = 0; e < r && !again; ++e)
            again = i >= ranges[e].i0 && i <= ranges[e].i1 && j >= ranges[e].j0 && j <= ranges[e].j1;
          if (again) continue;
          for (int n = 0; n < nodes; ++n) {
            if ((++tested & 255) == 0) poll_progress();
            const NodeId id{i, j, k, n};
            const std::int64_t index = lattice_.ball_index(id);
            if (index < 0) continue;
            ElementHit hit;
            hit.ball = lattice_.ball(id);
            hit.distance = distance_to_ball(query.center, hit.ball);
            if (!(hit.distance <= query.radius)) continue;
            hit.kind = n, hit.i = i, hit.j = j, hit.k = k, hit.index = index;
            if (!sink.on_hit(hit)) return tested;
          }
          for (int p = 0; p < patterns; ++p) {
            if ((++tested & 255) == 0) poll_progress();
            const BeamId id{i, j, k, p};
            const std::int64_t index = lattice_.beam_index(id);
            if (index < 0) continue;
            ElementHit hit;
            hit.is_beam = true;
            hit.beam = lattice_.beam(id);
            hit.distance = distance_to_beam(query.center, hit.beam);
            if (!(hit.distance <= query.radius)) continue;
            hit.kind = p, hit.i = i, hit.j = j, hit.k = k, hit.index = index;
            if (!sink.on_hit(hit)) return tested;
          }
        }
  }
  return tested;
}

BallQueryResult BecotsLatticeQuery::query_ball(const Ball& query) const {
  return detail::collect_hits(query, [&](HitSink& sink) { visit(query, sink); });
}

std::int64_t BecotsLatticeQuery::candidate_groups(const Ball& query) const {
  std::int64_t count = 0;
  for (const int k : candidate_layers(query))
    for (const GroupRange& r : layers_[static_cast<std::size_t>(k)].candidates(query)) count += r.count();
  return count;
}

std::optional<BecotsMap> becots_map_of(const Lattice& lattice, std::string* reason) {
  const auto refuse = [&](const std::string& why) {
    if (reason) *reason = why;
    return std::optional<BecotsMap>{};
  };
  const SteadyBrick* brick = lattice.layout().steady_brick();
  if (!brick) return refuse("the layout is not a steady brick");
  const Counts& counts = lattice.counts();
  if (!laid_in_becots_order(*brick, counts)) return refuse("the layers' step W is not applied first");
  if (brick->placement.map_distance(Similarity::identity()) > kSameStepTolerance)
    return refuse("the lattice has a placement");
  const Similarity &U = brick->step_along(0), &V = brick->step_along(1);
  const CanonicalForm cu = U.canonical(), cv = V.canonical();
  const auto has_apex = [](const CanonicalForm& c) {
    return c.kind == SimilarityKind::Swirl || c.kind == SimilarityKind::Dilation;
  };
  const auto turns = [](const CanonicalForm& c) {
    return c.kind == SimilarityKind::Swirl || c.kind == SimilarityKind::Rotation;
  };
  if (!has_apex(cu) && !has_apex(cv)) return refuse("neither U nor V dilates: no apex (a cylinder or a plane)");
  if (!turns(cu) && !turns(cv)) return refuse("neither U nor V turns: no axis");
  for (const CanonicalForm* c : {&cu, &cv})
    if (!has_apex(*c) && !turns(*c) && c->kind != SimilarityKind::Identity)
      return refuse(std::string("a step is a ") + to_string(c->kind) + ", not a spiral about the apex");
  const Vec3 apex = has_apex(cu) ? cu.point : cv.point;
  const Vec3 axis = glm::normalize(turns(cu) ? cu.axis : cv.axis);
  // The map's corner A: the first template node off the axis (from_field refuses one on it).
  for (const TemplateNode& node : lattice.definition().nodes) {
    const Vec3 fa = node.center - apex;
    if (!(glm::length(fa - glm::dot(fa, axis) * axis) > 1e-9 * glm::length(fa))) continue;
    const auto log_of = [&](const Similarity& s, std::int64_t count) {
      return static_cast<double>(count) * BecotsMap::Complex(s.log_scale(), glm::dot(s.rotation_vector(), axis));
    };
    try {
      return BecotsMap::from_field(apex, axis, node.center, log_of(U, counts.u), log_of(V, counts.v));
    } catch (const InvalidInput& e) {
      return refuse(std::string("no BeCOTS map through its steps: ") + e.what());
    }
  }
  return refuse("every template node lies on the spirals' axis");
}

}  // namespace steady
