#include "steady/query/becots_query.hpp"

#include <algorithm>

#include "steady/core/errors.hpp"
#include "steady/query/interference.hpp"

namespace steady {
namespace {
// How far the lattice's steps may be from the map's per-tile similarities (relative to the map's size, as
// map_distance measures) and still count as laid on that map: far above rounding, far below any other map.
constexpr double kSameStepTolerance = 1e-9;

// A ball holding the hull of two balls.
Ball bounding_ball(const Ball& a, const Ball& b) {
  return {0.5 * (a.center + b.center), 0.5 * glm::length(a.center - b.center) + std::max(a.radius, b.radius)};
}
}  // namespace

BecotsLatticeQuery::BecotsLatticeQuery(const Lattice& lattice, const BecotsMap& map) : lattice_(lattice) {
  const SteadyBrick* brick = lattice.layout().steady_brick();
  const Counts& counts = lattice.counts();
  const double du = 1.0 / static_cast<double>(counts.u), dv = 1.0 / static_cast<double>(counts.v);
  if (!brick || brick->axes != AxisOrder{2, 0, 1} ||
      brick->step_along(0).map_distance(map.field(du, 0.0)) > kSameStepTolerance ||
      brick->step_along(1).map_distance(map.field(0.0, dv)) > kSameStepTolerance ||
      brick->placement.map_distance(Similarity::identity()) > kSameStepTolerance)
    fail_input("lattice", "is not a BeCOTS lattice of this map (lay it with becots_lattice)");
  const Similarity& W = brick->step_along(2);
  if (W.kind() != SimilarityKind::Translation && W.kind() != SimilarityKind::Identity)
    fail_input("lattice", "its layers are not raised by a translation along the axis");
  // The template's bounding balls in group (0, 0, 0): its nodes, and around each beam it starts (the far end placed
  // by the step to its end group, whether or not that group exists: a bound only).
  const auto& def = lattice.definition();
  std::vector<Ball> balls;
  for (const TemplateNode& n : def.nodes) balls.push_back({n.center, n.radius});
  for (const BeamPattern& b : def.beams) {
    const Similarity to_end = map.field(b.di * du, b.dj * dv) * W.power(static_cast<double>(b.dk));
    const TemplateNode& from = def.nodes[static_cast<std::size_t>(b.from)];
    const TemplateNode& to = def.nodes[static_cast<std::size_t>(b.to)];
    balls.push_back(bounding_ball({from.center, from.radius}, to_end.apply(Ball{to.center, to.radius})));
  }
  for (std::int64_t k = 0; k < counts.w; ++k) {
    const Similarity raise = W.power(static_cast<double>(k));
    std::vector<Ball> layer;
    for (const Ball& b : balls) layer.push_back(raise.apply(b));
    layers_.emplace_back(map, std::move(layer), static_cast<int>(counts.u), static_cast<int>(counts.v), du, dv);
  }
}

BallQueryResult BecotsLatticeQuery::query_ball(const Ball& query) const {
  BallQueryResult out;
  const auto& def = lattice_.definition();
  const int nodes = static_cast<int>(def.nodes.size()), patterns = static_cast<int>(def.beams.size());
  for (std::int64_t k = 0; k < static_cast<std::int64_t>(layers_.size()); ++k)
    for (const GroupRange& r : layers_[static_cast<std::size_t>(k)].candidates(query))
      for (std::int64_t j = r.j0; j <= r.j1; ++j)
        for (std::int64_t i = r.i0; i <= r.i1; ++i) {
          for (int n = 0; n < nodes; ++n) {
            const NodeId id{i, j, k, n};
            const std::int64_t index = lattice_.ball_index(id);
            if (index >= 0 && distance_to_ball(query.center, lattice_.ball(id)) <= query.radius)
              out.balls.push_back(index);
          }
          for (int p = 0; p < patterns; ++p) {
            const BeamId id{i, j, k, p};
            const std::int64_t index = lattice_.beam_index(id);
            if (index >= 0 && distance_to_beam(query.center, lattice_.beam(id)) <= query.radius)
              out.beams.push_back(index);
          }
        }
  // Ranges of different turns may share groups when the lattice wraps around its axis: each element once.
  for (auto* v : {&out.balls, &out.beams}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  return out;
}

std::int64_t BecotsLatticeQuery::candidate_groups(const Ball& query) const {
  std::int64_t count = 0;
  for (const BecotsRangeFinder& layer : layers_)
    for (const GroupRange& r : layer.candidates(query)) count += r.count();
  return count;
}

}  // namespace steady
