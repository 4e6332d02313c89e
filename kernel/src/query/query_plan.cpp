// Which fast ball-interference paths a lattice allows: the numerical detection of the conditions of the
// paper's O(u) and O(1) BIQs, per normalized map.
//
// Element (i, j, k) is W'^k V'^j U'^i of the template (world steps X' = G X G^-1) in every lattice, so a
// normalized map of U' that V' and W' leave unchanged gives one i-range for all rows: O(u) needs such
// maps for V (kept by W') and W (kept by V'), O(1) for all three. The steps need not commute (the paper
// asks that they do); only a dilation map's beam extent, which depends on the beam's shape, is used for
// beams only when they do. A map M of X is unchanged by Y when Y preserves M's level sets; for each map
// type there is a closest map Y* that preserves it exactly (below), and the condition holds when Y and
// Y* differ by at most kConditionTolerance * L over the lattice's bound (L: its distance scale). The
// measured differences then make the paths exact anyway: with Y* in place of Y the invariance is exact,
// and j applications of Y instead of Y* move an element by at most j * mismatch * growth, so the query
// is inflated by that (QueryPlan::slabs_inflation, constant_inflation).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "query/query_internal.hpp"
#include "steady/core/rotation.hpp"
#include "steady/query/query_tolerance.hpp"

namespace steady::detail {

namespace {

// Largest displacement between two affine maps over a ball: at its center, plus the radius times the
// Frobenius norm of the difference of the linear parts.
double mismatch(const SimilarityTransform& a, const SimilarityTransform& b, const Ball& region) {
  const Vec3 d = a.apply_point(region.center) - b.apply_point(region.center);
  const Mat3 l = a.scale * a.rotation - b.scale * b.rotation;
  double f = 0.0;
  for (int c = 0; c < 3; ++c) f += glm::dot(l[c], l[c]);
  return glm::length(d) + region.radius * std::sqrt(f);
}

// The rotation taking unit vector `from` to unit vector `to` about their common normal.
Mat3 align(const Vec3& from, const Vec3& to) {
  const Vec3 axis = glm::cross(from, to);
  const double s = glm::length(axis), c = glm::dot(from, to);
  if (s < 1e-300) return c > 0.0 ? Mat3(1.0) : Mat3(1.0) * -1.0;  // opposite: no longer a rotation, mismatch is large anyway
  return axis_rotation(axis / s, c, s);
}

// The similarity closest to y that leaves map m exactly unchanged.
SimilarityTransform preserving(const SimilarityTransform& y, const NormalizedMap& m, const Ball& region) {
  SimilarityTransform out;
  const Vec3& a = m.axis;
  switch (m.type) {
    case NormalizedMap::Type::Translation: {
      // Keeps (x . a): no scaling, a rotation fixing a, no translation along a. Matched to y at the
      // region's center except along a.
      out.scale = 1.0;
      out.rotation = align(y.rotation * a, a) * y.rotation;
      const Vec3 c = region.center, yc = y.apply_point(c);
      const Vec3 target = yc - glm::dot(yc - c, a) * a;
      out.translation = target - out.rotation * c;
      break;
    }
    case NormalizedMap::Type::Dilation: {
      // Keeps |x - F|: the isometry x -> F + R (x - F).
      out.scale = 1.0;
      out.rotation = y.rotation;
      out.translation = m.point - y.rotation * m.point;
      break;
    }
    case NormalizedMap::Type::AxisDilation: {
      // Keeps the distance to the line: a rotation about it and a translation along it.
      out.scale = 1.0;
      out.rotation = align(y.rotation * a, a) * y.rotation;
      const Vec3 yp = y.apply_point(m.point);
      out.translation = m.point + glm::dot(yp - m.point, a) * a - out.rotation * m.point;
      break;
    }
    case NormalizedMap::Type::Rotation: {
      // Keeps the angle about the axis: no rotation, the axis mapped into itself.
      out.scale = y.scale;
      out.rotation = Mat3(1.0);
      const Vec3 yp = y.apply_point(m.point);
      out.translation = m.point + glm::dot(yp - m.point, a) * a - y.scale * m.point;
      break;
    }
  }
  return out;
}

struct Direction {
  const char* name;
  SimilarityTransform world;  // G X G^-1
  RowMotion motion;
  std::int64_t count;
  double log_scale;
  bool has_direction = false;  // a translation direction or a rotation axis
  Vec3 direction{0.0};
  Vec3 axis_point{0.0};
  bool axis_is_line = false;  // rotation axis (a line) rather than a free direction (translation)
};

Direction make_direction(const char* name, const SimilarityTransform& g, const SimilarityTransform& g_inv,
                         const Similarity& step, std::int64_t count) {
  Direction d{name, g * step.transform() * g_inv, RowMotion{}, count, step.log_scale()};
  d.motion = RowMotion::from(d.world);
  const CanonicalForm& c = d.motion.canonical();
  if (c.kind == SimilarityKind::Translation) {
    d.has_direction = true;
    d.direction = glm::normalize(c.translation);
  } else if (c.kind == SimilarityKind::Rotation || c.kind == SimilarityKind::Screw || c.kind == SimilarityKind::Swirl) {
    d.has_direction = true;
    d.direction = c.axis;
    d.axis_point = c.point;
    d.axis_is_line = true;
  }
  return d;
}

double distance_to_line(const Vec3& p, const Vec3& point, const Vec3& unit) {
  const Vec3 w = p - point;
  return glm::length(w - glm::dot(w, unit) * unit);
}

// True when the two maps are the same function of space (within a relative 1e-12).
bool same_map(const NormalizedMap& a, const NormalizedMap& b, double length_scale) {
  if (a.type != b.type) return false;
  const double e = 1e-12;
  switch (a.type) {
    case NormalizedMap::Type::Translation: {
      // (x - P) . a / d: compare the gradients a / d and the offsets P . a / d.
      const Vec3 ga = a.axis / a.step, gb = b.axis / b.step;
      return glm::length(ga - gb) <= e * glm::length(ga) &&
             std::abs(glm::dot(a.point, ga) - glm::dot(b.point, gb)) <= e * (1.0 + length_scale * glm::length(ga));
    }
    case NormalizedMap::Type::Dilation:
      return std::abs(a.step - b.step) <= e * std::abs(a.step) && glm::length(a.point - b.point) <= e * length_scale;
    case NormalizedMap::Type::AxisDilation:
    case NormalizedMap::Type::Rotation: {
      const Vec3 w = b.point - a.point;
      return std::abs(a.step - b.step) <= e * std::abs(a.step) && glm::length(glm::cross(a.axis, b.axis)) <= e &&
             glm::dot(a.axis, b.axis) > 0.0 && glm::length(w - glm::dot(w, a.axis) * a.axis) <= e * length_scale;
    }
  }
  return false;
}

void add_unique_map(RowMotion& m, const NormalizedMap& map, double length_scale) {
  for (const NormalizedMap& x : m.maps())
    if (same_map(x, map, length_scale)) return;
  m.add_map(map);
}

// Maps not in the paper that may survive where the canonical ones do not (see rangefinder.hpp).
void add_candidate_maps(Direction& x, const std::vector<const Direction*>& others, double tol) {
  const double length_scale = tol / kConditionTolerance;
  const CanonicalForm& c = x.motion.canonical();
  if (c.kind == SimilarityKind::Dilation) {
    // Distance to a line through F along another direction's axis (a rotation's axis must pass F).
    for (const Direction* y : others) {
      if (!y->has_direction) continue;
      if (y->axis_is_line && distance_to_line(c.point, y->axis_point, y->direction) > tol) continue;
      add_unique_map(x.motion, NormalizedMap::axis_dilation(c.point, y->direction, std::log(c.scale)), length_scale);
    }
  } else if (c.kind == SimilarityKind::Swirl) {
    add_unique_map(x.motion, NormalizedMap::axis_dilation(c.point, c.axis, std::log(c.scale)), length_scale);
  } else if (c.kind == SimilarityKind::Translation) {
    // Projections orthogonal to the other directions (the dual basis of a sheared regular lattice).
    std::vector<Vec3> dirs;
    for (const Direction* y : others)
      if (y->has_direction) dirs.push_back(y->direction);
    std::vector<Vec3> normals;
    if (dirs.size() == 2) normals.push_back(glm::cross(dirs[0], dirs[1]));
    for (const Vec3& d : dirs) normals.push_back(c.translation - glm::dot(c.translation, d) * d);
    for (Vec3 n : normals) {
      const double len = glm::length(n);
      if (len < 1e-9) continue;
      n /= len;
      const double step = glm::dot(c.translation, n);
      if (std::abs(step) < 1e-6 * glm::length(c.translation)) continue;
      add_unique_map(x.motion, NormalizedMap::translation(Vec3(0.0), n, step), length_scale);
    }
  }
}

// Keeps the maps of x that every other direction leaves unchanged (within tol); returns the inflation
// the kept maps need: sum over others of (count - 1) * mismatch. A dilation map is also dropped for
// beams unless the steps commute (`commuting`): its beam extent includes the nearest point of the cone,
// which is only carried over when every beam is a similar copy of the template beam. The other maps'
// beam extents follow from their two balls' extents (translation) or from the beam's shadow along the
// axis, which all the steps involved map as similarities about one axis point (rotation, axis distance).
double keep_invariant_maps(Direction& x, const std::vector<const Direction*>& others, const Ball& region, double tol,
                           bool commuting, bool has_beams) {
  double inflation = 0.0;
  RowMotion& m = x.motion;
  for (std::size_t idx = m.maps().size(); idx-- > 0;) {
    const NormalizedMap& map = m.maps()[idx];
    double worst = 0.0, need = 0.0;
    for (const Direction* y : others) {
      if (y->count <= 1) continue;  // never applied
      const double mm = mismatch(y->world, preserving(y->world, map, region), region);
      worst = std::max(worst, mm);
      need += static_cast<double>(y->count - 1) * mm;
    }
    const bool shape_dependent = map.type == NormalizedMap::Type::Dilation && has_beams && !commuting;
    if (worst > tol || shape_dependent)
      m.remove_map(idx);
    else
      inflation = std::max(inflation, need);
  }
  m.set_identity_tests_template(false);
  return inflation;
}

std::string map_names(const RowMotion& m) {
  if (m.kind() == SimilarityKind::Identity) return "identity";
  std::string s;
  for (const NormalizedMap& map : m.maps()) {
    if (!s.empty()) s += "+";
    switch (map.type) {
      case NormalizedMap::Type::Translation: s += "T"; break;
      case NormalizedMap::Type::Dilation: s += "D"; break;
      case NormalizedMap::Type::AxisDilation: s += "Daxis"; break;
      case NormalizedMap::Type::Rotation: s += "R"; break;
    }
  }
  return s.empty() ? "none" : s;
}

}  // namespace

void detect_plan(QueryState& q) {
  const Lattice& lat = q.lattice;
  const Counts& c = lat.counts();
  QueryPlan& plan = q.plan;
  const SteadyBrick& brick = *lat.layout().steady_brick();
  const Similarity &G = brick.placement, &U_step = brick.steps[0], &V_step = brick.steps[1], &W_step = brick.steps[2];
  const SimilarityTransform g = G.transform();
  const SimilarityTransform g_inv = G.inverse().transform();
  const Ball region{q.bound.center, q.bound.radius * 2.0};  // ideal points stay near the lattice
  const double tol = kConditionTolerance * q.length_scale;
  const double growth = std::exp(std::abs(U_step.log_scale()) * static_cast<double>(c.u - 1) +
                                 std::abs(V_step.log_scale()) * static_cast<double>(c.v - 1) +
                                 std::abs(W_step.log_scale()) * static_cast<double>(c.w - 1));

  Direction U = make_direction("U", g, g_inv, U_step, c.u);
  Direction V = make_direction("V", g, g_inv, V_step, c.v);
  Direction W = make_direction("W", g, g_inv, W_step, c.w);
  plan.rows_w = W.motion;

  // Commutators only matter between directions that both step.
  auto commutator = [&](const Direction& a, const Direction& b) {
    return a.count <= 1 || b.count <= 1 ? 0.0 : mismatch(a.world * b.world, b.world * a.world, region);
  };
  const double uv = commutator(U, V), uw = commutator(U, W), vw = commutator(V, W);
  plan.largest_commutator = std::max({uv, uw, vw});
  auto usable = [](const Direction& d) { return d.count <= 1 || !d.motion.maps().empty(); };
  auto steps = [](const Direction& d) { return static_cast<double>(std::max<std::int64_t>(0, d.count - 1)); };

  const bool has_beams = lat.pattern_count() > 0;
  // O(u), per slab i: elements W'^k V'^j (G U^i t); V's maps unchanged by W', W's by V'.
  {
    Direction v = V, w = W;
    add_candidate_maps(v, {&U, &W}, tol);
    add_candidate_maps(w, {&U, &V}, tol);
    const bool commuting = vw <= tol;
    const double inflate_v = keep_invariant_maps(v, {&W}, region, tol, commuting, has_beams);
    const double inflate_w = keep_invariant_maps(w, {&V}, region, tol, commuting, has_beams);
    std::ostringstream why;
    if (!usable(v)) why << "no normalized map of V is left unchanged by W";
    else if (!usable(w)) why << "no normalized map of W is left unchanged by V";
    plan.slabs_reason = why.str();
    plan.slabs_valid = plan.slabs_reason.empty();
    plan.slabs_v = v.motion;
    plan.slabs_w = w.motion;
    plan.slabs_inflation = 2.0 * growth * ((commuting ? steps(V) * steps(W) * vw : 0.0) + inflate_v + inflate_w);
  }
  // O(1): elements W'^k V'^j U'^i (G t). An i-range from U's maps unchanged by V' and W'; j- and
  // k-ranges from the template at (0,0,0) when V's and W's maps are also unchanged by U', otherwise
  // per candidate slab i as in O(u).
  {
    Direction u = U, v = V, w = W;
    add_candidate_maps(u, {&V, &W}, tol);
    add_candidate_maps(v, {&U, &W}, tol);
    add_candidate_maps(w, {&U, &V}, tol);
    const bool commuting = std::max({uv, uw, vw}) <= tol;
    const double inflate_u = keep_invariant_maps(u, {&V, &W}, region, tol, commuting, has_beams);
    const double inflate_v = keep_invariant_maps(v, {&U, &W}, region, tol, commuting, has_beams);
    const double inflate_w = keep_invariant_maps(w, {&U, &V}, region, tol, commuting, has_beams);
    const double commutators = commuting ? steps(U) * steps(V) * uv + steps(U) * steps(W) * uw + steps(V) * steps(W) * vw : 0.0;
    plan.constant_u = u.motion;
    plan.constant_v = v.motion;
    plan.constant_w = w.motion;
    plan.constant_per_slab = !(usable(v) && usable(w));
    std::ostringstream why;
    if (!usable(u)) why << "no normalized map of U is left unchanged by V and W";
    else if (plan.constant_per_slab && !plan.slabs_valid) why << plan.slabs_reason;
    plan.constant_reason = why.str();
    plan.constant_valid = plan.constant_reason.empty();
    plan.constant_inflation = 2.0 * growth * (commutators + inflate_u + inflate_v + inflate_w);
    if (plan.constant_per_slab) plan.constant_inflation = std::max(plan.constant_inflation, plan.slabs_inflation + 2.0 * growth * inflate_u);
  }
  plan.automatic = plan.constant_valid ? QueryMethod::Constant : QueryMethod::Blocks;
}

}  // namespace steady::detail

namespace steady {

std::string QueryPlan::describe() const {
  std::ostringstream os;
  os << "rows (O(uv)): W maps " << detail::map_names(rows_w) << "; ";
  os << "slabs (O(u)): ";
  if (slabs_valid)
    os << "yes, V " << detail::map_names(slabs_v) << ", W " << detail::map_names(slabs_w);
  else
    os << "no (" << slabs_reason << ")";
  os << "; constant (O(1)): ";
  if (constant_valid && !constant_per_slab)
    os << "yes, U " << detail::map_names(constant_u) << ", V " << detail::map_names(constant_v) << ", W "
       << detail::map_names(constant_w);
  else if (constant_valid)
    os << "yes, U " << detail::map_names(constant_u) << ", then per candidate slab V " << detail::map_names(slabs_v)
       << ", W " << detail::map_names(slabs_w);
  else
    os << "no (" << constant_reason << ")";
  os << "; becots (O(1) on a BeCOTS slab or stack): " << (becots_valid ? "yes" : "no (" + becots_reason + ")");
  os << "; auto: " << to_string(automatic);
  return os.str();
}

}  // namespace steady
