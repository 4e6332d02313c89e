#include "steady/query/queries.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "query/hit_sinks.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/numeric_range.hpp"
#include "steady/query/interference.hpp"
#include "steady/core/memory_budget.hpp"
#include "steady/core/progress.hpp"

namespace steady {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Rays: the search ball grows when it finds nothing and shrinks when it finds many elements, so a step
// costs about one small query wherever the ray is; these bound the factor and set the target.
constexpr int kRayCrowdedHits = 24;
constexpr double kRayFirstStepScale = 4.0;  // first search radius, in element sizes
// Distances: the first search radius in element sizes, then x4 until something is found.
constexpr double kDistanceFirstScale = 2.0;

Vec3 point_at(const double* p, std::size_t i, const char* field) {
  const Vec3 v(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  for (int c = 0; c < 3; ++c)
    if (!(std::abs(v[c]) <= kMaxCoordinate))  // NaN fails too
      require_within(v, kMaxCoordinate, std::string(field) + "[" + std::to_string(i) + "]");
  return v;
}

void validate_points(const double* p, std::size_t n, const char* field) {
  for (std::size_t i = 0; i < n; ++i) point_at(p, i, field);
}

struct NearestSink : HitSink {
  double best = kInf;
  bool on_hit(const ElementHit& h) override {
    best = std::min(best, std::max(0.0, h.distance));
    return best > 0.0;  // inside an element: nothing can be nearer
  }
  double reach() const override { return best; }
};

struct RaySink : HitSink {
  Vec3 origin, direction;
  double best = kInf;
  int hits = 0;
  bool on_hit(const ElementHit& h) override {
    ++hits;
    const double s = h.is_beam ? ray_enters_beam(origin, direction, h.beam) : ray_enters_ball(origin, direction, h.ball);
    best = std::min(best, s);
    return best > 0.0;
  }
};

// Parameters [t0, t1] of the ray inside the ball, or false.
bool clip_to_ball(const Vec3& o, const Vec3& d, const Ball& b, double* t0, double* t1) {
  const Vec3 w = o - b.center;
  const double half_b = glm::dot(w, d);
  const double c = glm::dot(w, w) - b.radius * b.radius;
  const double disc = half_b * half_b - c;
  if (disc < 0.0) return false;
  const double s = std::sqrt(disc);
  *t0 = -half_b - s;
  *t1 = -half_b + s;
  return *t1 >= 0.0;
}

double first_hit(const InterferenceSource& src, const Vec3& origin, const Vec3& dir, double max_distance,
                 const Ball& bound, double scale) {
  double t0, t1;
  if (!clip_to_ball(origin, dir, bound, &t0, &t1)) return kInf;
  double t = std::max(0.0, t0);
  const double t_end = std::min(max_distance, t1);
  double radius = kRayFirstStepScale * scale;
  while (t <= t_end) {
    RaySink sink;
    sink.origin = origin + t * dir;
    sink.direction = dir;
    src.visit(Ball{sink.origin, radius}, sink);
    // Every element meeting the segment [t, t + radius] meets the ball: the least entry found is the hit.
    if (sink.best <= radius) {
      const double hit = t + sink.best;
      return hit <= max_distance ? hit : kInf;
    }
    t += radius;
    if (sink.hits == 0)
      radius = std::min(2.0 * radius, bound.radius);
    else if (sink.hits > kRayCrowdedHits)
      radius = std::max(0.5 * radius, 0.25 * scale);
  }
  return kInf;
}

}  // namespace

LatticeSource::LatticeSource(const LatticeQuery& query, QueryMethod method)
    : query_(query), method_(query.resolve(method)), scale_(typical_element_size(query.lattice())) {}

void LatticeSource::visit_nearest(const Ball& query, HitSink& sink) const {
  // The hierarchical path visits nearer blocks first and prunes by the sink's reach; the naive path (an
  // explicit choice, or a layout without a steady brick) scans everything anyway.
  const bool blocks = method_ != QueryMethod::Naive && query_.plan().steady_reason.empty();
  query_.visit(query, sink, blocks ? QueryMethod::Blocks : method_);
}

double typical_element_size(const Lattice& lattice) {
  double r = 0.0;
  for (const auto& n : lattice.definition().nodes) r += n.radius;
  r /= static_cast<double>(lattice.node_count());
  const double mean_log_scale = lattice.layout().mean_log_scale();
  return r * std::exp(mean_log_scale);
}

void contains(const InterferenceSource& source, const double* points, std::size_t n, std::uint8_t* inside) {
  validate_points(points, n, "points");
  Progress* const caller = current_progress();
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    const ProgressScope scope(caller);
    poll_progress();
    detail::FirstHitSink sink;
    source.visit(Ball{point_at(points, i, "points"), 0.0}, sink);
    inside[i] = sink.found ? 1 : 0;
  });
}

void distance(const InterferenceSource& source, const double* points, std::size_t n, double bound, double* out) {
  validate_points(points, n, "points");
  if (std::isnan(bound) || bound < 0.0) fail_input("bound", "must be >= 0 (got " + std::to_string(bound) + ")");
  const double first = kDistanceFirstScale * source.element_scale();
  const Ball lattice_bound = source.bound();
  Progress* const caller = current_progress();
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    const ProgressScope scope(caller);
    poll_progress();
    const Vec3 p = point_at(points, i, "points");
    // Every element lies within `far` of p: no search goes beyond it (nor beyond the caller's bound).
    const double far = glm::length(p - lattice_bound.center) + lattice_bound.radius;
    const double limit = std::min(bound, far);
    // Near the lattice one small query answers.
    const double r = std::min(limit, first);
    NearestSink near;
    source.visit(Ball{p, r}, near);
    if (near.best <= r) {  // every element nearer than r was visited: the least distance found is the distance
      out[i] = near.best;
      return;
    }
    // Farther: one search to the limit, nearer blocks first, pruned by the best distance so far.
    NearestSink nearest;
    if (r < limit) source.visit_nearest(Ball{p, limit}, nearest);
    out[i] = nearest.best <= limit ? nearest.best : kInf;
  });
}

void raycast(const InterferenceSource& source, const double* origins, const double* directions, std::size_t n,
             double max_distance, double* t) {
  validate_points(origins, n, "origins");
  validate_points(directions, n, "directions");
  if (std::isnan(max_distance) || max_distance <= 0.0)
    fail_input("max_distance", "must be > 0 (got " + std::to_string(max_distance) + ")");
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 d = point_at(directions, i, "directions");
    if (!(glm::length(d) > 0.0)) fail_input("directions[" + std::to_string(i) + "]", "must be a non-zero vector");
  }
  const Ball bound = source.bound();
  const double scale = source.element_scale();
  Progress* const caller = current_progress();
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    const ProgressScope scope(caller);
    poll_progress();
    const Vec3 d = point_at(directions, i, "directions");
    t[i] = first_hit(source, point_at(origins, i, "origins"), d / glm::length(d), max_distance, bound, scale);
  });
}

void voxelize(const InterferenceSource& source, const Vec3& lo, const Vec3& hi, const std::int64_t shape[3],
              std::uint8_t* out) {
  for (int c = 0; c < 3; ++c) {
    require_finite(lo[c], "lo");
    require_finite(hi[c], "hi");
    if (!(hi[c] > lo[c])) fail_input("hi", "must exceed lo in every coordinate");
    if (shape[c] < 1) fail_input("shape", "every count must be >= 1 (got " + std::to_string(shape[c]) + ")");
  }
  const std::int64_t nx = shape[0], ny = shape[1], nz = shape[2];
  const Vec3 cell = (hi - lo) / Vec3(static_cast<double>(nx), static_cast<double>(ny), static_cast<double>(nz));
  Progress* const caller = current_progress();
  tbb::parallel_for(std::int64_t(0), nx * ny, [&](std::int64_t row) {
    const ProgressScope scope(caller);
    poll_progress();
    const std::int64_t ix = row / ny, iy = row % ny;
    for (std::int64_t iz = 0; iz < nz; ++iz) {
      const Vec3 p = lo + (Vec3(static_cast<double>(ix), static_cast<double>(iy), static_cast<double>(iz)) + 0.5) * cell;
      detail::FirstHitSink sink;
      source.visit(Ball{p, 0.0}, sink);
      out[row * nz + iz] = sink.found ? 1 : 0;
    }
  });
}

}  // namespace steady
