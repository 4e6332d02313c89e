// Fuzz target: the query and geometry entry points on small random lattices built from the fuzz bytes. A lattice
// of 1 to 3 nodes, up to 6 beam patterns (with or without end radii), 1 to 5 groups along each direction, steps of
// every kind (translation, rotation, screw, dilation, swirl, near-identity, a raw generator), incremental or
// cumulative, applied in any order, a placement and omitted nodes; now and then a raw double (NaN, infinities,
// 1e300) replaces a parameter, which the kernel must refuse with InvalidInput. On a lattice it accepts, against
// brute force over every element listed (tests/common/query_oracle.hpp):
//   query_ball and touches, every query path that applies     the same element sets (exact)
//   contains (point membership)                               the same answer (exact)
//   distance with a bound                                     the same distance (to rounding), inf beyond the bound
//   raycast with a maximum distance                           the same first hit (to rounding; grazing rays,
//                                                             whose depth in the element is at rounding level, may
//                                                             go either way)
//   lattice_properties (sums only)                            the brute-force sum of hubs (1e-7 relative)
// Any disagreement is a finding (a silent wrong answer) and aborts.
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_common.hpp"
#include "query_oracle.hpp"
#include "steady/core/constants.hpp"
#include "steady/properties/lattice_properties.hpp"
#include "steady/query/interference.hpp"
#include "steady/query/lattice_query.hpp"
#include "steady/query/queries.hpp"

namespace {

using namespace steady;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::int64_t kMaxPropertyBalls = 24;

// Numbers from the fuzz bytes: mostly in a sane range, now and then any double at all.
struct Numbers {
  FuzzedDataProvider& in;
  double unit() { return in.ConsumeProbability<double>(); }
  double within(double a) {
    if (in.ConsumeIntegralInRange<int>(0, 63) == 0) return in.ConsumeFloatingPoint<double>();  // wild
    return (2.0 * unit() - 1.0) * a;
  }
  Vec3 vec(double a) { return {within(a), within(a), within(a)}; }
  Vec3 unit_vec() {
    Vec3 v(2 * unit() - 1, 2 * unit() - 1, 2 * unit() - 1);
    return glm::length(v) > 1e-3 ? v : Vec3(0, 0, 1);
  }
};

Similarity step(Numbers& n, const Vec3& along) {
  const double angle = n.within(0.7), scale = std::exp(n.within(0.2));
  const Vec3 axis = n.unit_vec(), point = n.vec(3.0);
  switch (n.in.ConsumeIntegralInRange<int>(0, 8)) {
    case 0: return Similarity::translation(along + n.vec(0.3));
    case 1: return Similarity::rotation(angle, axis, point + along * 4.0);
    case 2: return Similarity::screw(angle, axis, point, n.within(2.0));
    case 3: return Similarity::dilation(1.0 + 0.3 * n.unit(), point - along * 5.0);
    case 4: return Similarity::swirl(angle, axis, point, scale);
    case 5: return Similarity::translation(along) * Similarity::swirl(0.3 * angle, axis, point, std::sqrt(scale));
    case 6: return Similarity::translation(along) * Similarity::rotation(1e-7 * angle, axis, point);
    case 7: return Similarity::rotation(2 * kPi - 1e-4 * n.unit(), axis, point) * Similarity::translation(along);
    default: return Similarity::from_generator(n.within(0.3), n.vec(1.0), along + n.vec(0.5));
  }
}

Lattice make_lattice(Numbers& n) {
  FuzzedDataProvider& in = n.in;
  std::vector<TemplateNode> nodes(static_cast<std::size_t>(in.ConsumeIntegralInRange<int>(1, 3)));
  for (TemplateNode& t : nodes) t = {n.vec(0.5), 0.02 + 0.2 * n.unit()};
  if (in.ConsumeBool()) nodes[0].radius = n.within(0.3);
  std::vector<BeamPattern> beams(static_cast<std::size_t>(in.ConsumeIntegralInRange<int>(0, 6)));
  const int last = static_cast<int>(nodes.size()) - 1;
  for (BeamPattern& b : beams) {
    b.from = in.ConsumeIntegralInRange<int>(0, last);
    b.to = in.ConsumeIntegralInRange<int>(0, last);
    b.di = in.ConsumeIntegralInRange<int>(-1, 2);
    b.dj = in.ConsumeIntegralInRange<int>(-1, 1);
    b.dk = in.ConsumeIntegralInRange<int>(-1, 1);
    if (in.ConsumeBool()) {
      b.from_radius = nodes[static_cast<std::size_t>(b.from)].radius * (0.2 + 0.8 * n.unit());
      b.to_radius = nodes[static_cast<std::size_t>(b.to)].radius * (0.2 + 0.8 * n.unit());
    }
  }
  const Counts counts{in.ConsumeIntegralInRange<std::int64_t>(1, 5), in.ConsumeIntegralInRange<std::int64_t>(1, 5),
                      in.ConsumeIntegralInRange<std::int64_t>(1, 5)};
  DirectionControl c[3];
  const Vec3 axes[3] = {{1.2, 0, 0}, {0, 1.2, 0}, {0, 0, 1.2}};
  for (int a = 0; a < 3; ++a) {
    const bool cumulative = in.ConsumeIntegralInRange<int>(0, 3) == 0;
    const double span = cumulative ? static_cast<double>(counts.along(a) - 1) : 1.0;
    c[a] = {step(n, axes[a] * std::max(1.0, span)), cumulative ? StepControl::Cumulative : StepControl::Incremental};
  }
  const Similarity placement = Similarity::from_generator(n.within(0.5), n.vec(3.0), n.vec(10.0));
  static const AxisOrder kOrders[6] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const AxisOrder order = kOrders[in.ConsumeIntegralInRange<int>(0, 5)];
  std::vector<NodeId> omitted(static_cast<std::size_t>(in.ConsumeIntegralInRange<int>(0, 3)));
  for (NodeId& id : omitted)
    id = {in.ConsumeIntegralInRange<std::int64_t>(0, counts.u - 1), in.ConsumeIntegralInRange<std::int64_t>(0, counts.v - 1),
          in.ConsumeIntegralInRange<std::int64_t>(0, counts.w - 1), in.ConsumeIntegralInRange<int>(0, last)};
  return Lattice::ordered(std::move(nodes), std::move(beams), counts, c[0], c[1], c[2], placement, order,
                          std::move(omitted));
}

std::string describe(const Ball& q) {
  std::ostringstream os;
  os.precision(17);
  os << "query (" << q.center.x << ", " << q.center.y << ", " << q.center.z << ") r " << q.radius;
  return os.str();
}

// A query ball: near an element (often touching it or a point), or anywhere in the lattice's bound.
Ball make_query(Numbers& n, const Lattice& lat, const Ball& bound) {
  const std::int64_t x = n.in.ConsumeIntegralInRange<std::int64_t>(0, lat.ball_count() - 1);
  const Ball e = lat.ball(lat.ball_id(x));
  Ball q;
  switch (n.in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0:
      q.center = bound.center + n.vec(bound.radius);
      q.radius = n.unit() * 0.3 * bound.radius;
      break;
    case 1:  // touching the ball from outside
      q.center = e.center + n.unit_vec() * e.radius * (1.0 + 2.0 * n.unit());
      q.radius = std::max(0.0, glm::length(q.center - e.center) - e.radius);
      break;
    default:
      q.center = e.center + n.vec(3.0 * e.radius);
      q.radius = n.in.ConsumeBool() ? 0.0 : 2.0 * e.radius * n.unit();
  }
  return q;
}

void check_ball_queries(const LatticeQuery& lq, const test::BruteForceQuery& brute, const Ball& q) {
  const BallQueryResult truth = brute(q);
  const bool any = !truth.balls.empty() || !truth.beams.empty();
  for (QueryMethod m : {QueryMethod::Auto, QueryMethod::Naive, QueryMethod::Rows, QueryMethod::Blocks,
                        QueryMethod::PaperRows, QueryMethod::Slabs, QueryMethod::PaperSlabs, QueryMethod::Constant}) {
    try {
      lq.resolve(m);
    } catch (const InvalidInput&) {
      continue;  // this path does not apply to this lattice
    }
    const BallQueryResult r = lq.query_ball(q, m);
    if (r.balls != truth.balls || r.beams != truth.beams)
      fuzz::finding(std::string("query_ball, method ") + to_string(m) + ": " + std::to_string(r.balls.size()) + "+" +
                    std::to_string(r.beams.size()) + " elements, brute force " + std::to_string(truth.balls.size()) +
                    "+" + std::to_string(truth.beams.size()) + "; " + describe(q) + "\n" + lq.plan().describe());
    if (lq.touches(q, m) != any) fuzz::finding(std::string("touches disagrees, method ") + to_string(m) + "; " + describe(q));
  }
}

double brute_distance(const test::BruteForceQuery& brute, const Vec3& p) {
  double best = kInf;
  for (const Ball& b : brute.balls) best = std::min(best, std::max(0.0, distance_to_ball(p, b)));
  for (const BeamGeometry& g : brute.beams) best = std::min(best, std::max(0.0, distance_to_beam(p, g)));
  return best;
}

double brute_ray(const test::BruteForceQuery& brute, const Vec3& o, const Vec3& d) {
  double best = kInf;
  for (const Ball& b : brute.balls) best = std::min(best, ray_enters_ball(o, d, b));
  for (const BeamGeometry& g : brute.beams) best = std::min(best, ray_enters_beam(o, d, g));
  return best;
}

// How deep the ray goes into the lattice just past parameter t (the least signed distance over a few steps):
// a ray that misses or hits only at rounding depth is grazing.
double depth_after(const test::BruteForceQuery& brute, const Vec3& o, const Vec3& d, double t, double step) {
  double least = kInf;
  for (int s = 0; s <= 8; ++s) {
    const Vec3 p = o + (t + step * s / 8.0) * d;
    for (const Ball& b : brute.balls) least = std::min(least, distance_to_ball(p, b));
    for (const BeamGeometry& g : brute.beams) least = std::min(least, distance_to_beam(p, g));
  }
  return least;
}

void check_point_queries(const LatticeSource& source, const test::BruteForceQuery& brute, Numbers& n,
                         const Ball& q, const Ball& bound, double scale) {
  const double p[3] = {q.center.x, q.center.y, q.center.z};
  // Rounding allowance: distances and ray parameters are computed from coordinates of size `extent`.
  const double extent = glm::length(q.center - bound.center) + bound.radius;
  const double tol = 1e-9 * extent;

  std::uint8_t inside = 0;
  contains(source, p, 1, &inside);
  if ((inside != 0) != brute.meets({q.center, 0.0})) fuzz::finding("contains disagrees; " + describe(q));

  const double bound_d = n.in.ConsumeBool() ? kInf : n.unit() * 2.0 * bound.radius;
  double d = 0.0;
  distance(source, p, 1, bound_d, &d);
  const double truth = brute_distance(brute, q.center);
  const bool beyond = truth > bound_d;
  const bool near_bound = std::abs(truth - bound_d) <= tol;
  if (!near_bound && (beyond ? d != kInf : !(std::abs(d - truth) <= tol)))
    fuzz::finding("distance " + std::to_string(d) + ", brute force " + std::to_string(truth) + " (bound " +
                  std::to_string(bound_d) + "); " + describe(q));

  const Vec3 dir = n.unit_vec();
  const double direction[3] = {dir.x, dir.y, dir.z};
  const double max_t = n.in.ConsumeBool() ? kInf : 0.01 + n.unit() * 2.0 * extent;
  double t = 0.0;
  raycast(source, p, direction, 1, max_t, &t);
  const Vec3 u = dir / glm::length(dir);
  double ray_truth = brute_ray(brute, q.center, u);
  if (ray_truth > max_t) ray_truth = kInf;
  if (t == ray_truth || (std::isfinite(t) && std::isfinite(ray_truth) && std::abs(t - ray_truth) <= tol)) return;
  // One of them hit, or they hit far apart: the ray must be grazing there (or cut by max_distance).
  const double first = std::min(t, ray_truth), second = std::max(t, ray_truth);
  const bool grazing = depth_after(brute, q.center, u, first, std::min(second - first, scale)) >= -1e-6 * scale;
  const bool at_cut = std::abs(first - max_t) <= tol;
  if (!grazing && !at_cut)
    fuzz::finding("raycast t " + std::to_string(t) + ", brute force " + std::to_string(ray_truth) + " (max " +
                  std::to_string(max_t) + "); " + describe(q) + " direction (" + std::to_string(u.x) + ", " +
                  std::to_string(u.y) + ", " + std::to_string(u.z) + ")");
}

double property_difference(const LatticeProperties& a, const LatticeProperties& b) {
  auto max_abs = [](const Mat3& m) {
    double x = 0.0;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) x = std::max(x, std::abs(m[r][c]));
    return x;
  };
  const double size = std::sqrt(std::max(1e-300, a.inertia[0][0] + a.inertia[1][1] + a.inertia[2][2]) / a.volume);
  double d = std::abs(a.volume - b.volume) / a.volume;
  d = std::max(d, std::abs(a.area - b.area) / a.area);
  d = std::max(d, glm::length(a.centroid - b.centroid) / size);
  return std::max(d, max_abs(a.inertia - b.inertia) / max_abs(a.inertia));
}

void check_properties(const Lattice& lat) {
  LatticePropertiesOptions sums_only;  // both sides sum hubs; the clean check is not what is compared here
  sums_only.check_clean = false;
  std::optional<LatticeProperties> brute;
  std::string brute_refusal, fast_refusal;
  try {
    brute = lattice_properties_brute_force(lat, sums_only);
  } catch (const InvalidInput& e) {
    brute_refusal = e.what();
  }
  std::optional<LatticeProperties> fast;
  try {
    fast = lattice_properties(lat, sums_only);
  } catch (const InvalidInput& e) {
    fast_refusal = e.what();
  }
  if (brute.has_value() != fast.has_value())
    fuzz::finding(std::string("lattice_properties ") + (fast ? "accepts" : "refuses") + " a lattice the brute force " +
                  (brute ? "accepts" : "refuses") + ": " + fast_refusal + brute_refusal);
  if (!brute) return;
  const double d = property_difference(*brute, *fast);
  if (!(d <= 1e-7))
    fuzz::finding("lattice_properties differs from the brute-force sum by " + std::to_string(d) + " (volume " +
                  std::to_string(fast->volume) + " vs " + std::to_string(brute->volume) + ")");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  Numbers n{in};
  std::optional<Lattice> lattice;
  fuzz::refusals_only("random lattice", [&] { lattice.emplace(make_lattice(n)); });
  if (!lattice || lattice->ball_count() == 0) return 0;
  fuzz::budget_refusals_only("queries", [&] {
    const Lattice& lat = *lattice;
    const LatticeQuery lq(lat);
    const LatticeSource source(lq);
    const test::BruteForceQuery brute(lat);
    const Ball bound = lq.bound();
    const double scale = typical_element_size(lat);
    const int queries = in.ConsumeIntegralInRange<int>(1, 6);
    for (int k = 0; k < queries; ++k) {
      const Ball q = make_query(n, lat, bound);
      try {
        validate_query_ball(q, "query");
      } catch (const InvalidInput&) {
        continue;  // a wild number made the query itself out of range: refusing it is right
      }
      check_ball_queries(lq, brute, q);
      check_point_queries(source, brute, n, q, bound, scale);
    }
    // Properties of hubs whose caps overlap are integrated by adaptive quadrature, seconds per lattice under ASan
    // for both sums: only small lattices, so that one input stays well under the hang timeout.
    if (lat.ball_count() <= kMaxPropertyBalls && in.ConsumeBool()) check_properties(lat);
  });
  return 0;
}
