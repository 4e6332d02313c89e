#include "brep/sphere_layout.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "lattice/circle_frames.hpp"
#include "steady/core/errors.hpp"

namespace steady {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
// Candidate poles: a Fibonacci covering of the sphere (plus the caps' axes and their antipodes); candidate seam
// longitudes: evenly spaced around each pole. 96 x 36 frames keep the layout of a 26-beam hub under a millisecond.
constexpr int kFibonacciPoles = 96;
constexpr int kSeamLongitudes = 36;
// Near the ends of a pole circle's parameter range the longitude may wrap by rounding; values within this of 0 or
// 2 pi are moved to the branch the parameter calls for (the longitude moves at least margin-fast there).
constexpr double kWrapSlack = 1e-3;

double angle_between(const Vec3& a, const Vec3& b) { return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)); }


struct SphereFrame {
  Vec3 z, x, y;
};

// Seam crossings of a circle: parameters t with p(t) on the half meridian {y = 0, x > 0}.
std::vector<double> seam_crossings(const CircleLayout& c, const SphereFrame& f) {
  const double a = c.rho * glm::dot(c.e1, f.y), b = c.rho * glm::dot(c.e2, f.y);
  const double rhs = -c.cap.exit * glm::dot(c.cap.direction, f.y);
  const double r = std::hypot(a, b);
  std::vector<double> out;
  if (!(r > std::abs(rhs))) return out;
  const double phi = std::atan2(b, a), beta = std::acos(rhs / r);
  for (double t : {phi - beta, phi + beta})
    if (glm::dot(c.point(t), f.x) > 0.0) out.push_back(t);
  return out;
}

struct Evaluation {
  bool usable = false;
  double margin = 0.0;
  int crossing_circles = 0;
  int straddles = 0;  // circles crossing the seam twice
};

Evaluation evaluate(const std::vector<CircleLayout>& circles, const SphereFrame& f) {
  Evaluation e;
  double margin = M_PI;
  for (const CircleLayout& c : circles) {
    const double theta = std::acos(std::clamp(c.cap.exit, -1.0, 1.0));
    const double to_north = angle_between(f.z, c.cap.direction);
    margin = std::min({margin, std::abs(to_north - theta), std::abs(M_PI - to_north - theta)});
    const bool north = to_north < theta, south = M_PI - to_north < theta;
    if (north && south) return e;
    // Tangency of the circle with the seam's great circle, where it matters (on the seam's half).
    const double off_plane = glm::dot(c.cap.direction, f.y);
    const Vec3 foot = c.cap.direction - off_plane * f.y;
    if (glm::dot(foot, f.x) > 0.0 || glm::length(foot) < 1e-9)
      margin = std::min(margin, std::abs(theta - std::asin(std::min(1.0, std::abs(off_plane)))));
    const std::size_t n = seam_crossings(c, f).size();
    if ((north || south) ? n != 1 : (n != 0 && n != 2)) return e;
    if (n > 0) ++e.crossing_circles;
    if (n == 2) ++e.straddles;
  }
  e.usable = true;
  e.margin = margin;
  return e;
}

}  // namespace

Vec3 CircleLayout::point(double t) const {
  return cap.exit * cap.direction + rho * (std::cos(t) * e1 + std::sin(t) * e2);
}

void SphereLayout::uv(int circle, ArcBranch branch, double t, double out[2], int derivative) const {
  const CircleLayout& c = circles[circle];
  const Vec3 y = glm::cross(z, x);
  const double ct = std::cos(t), st = std::sin(t);
  const Vec3 p = c.cap.exit * c.cap.direction + c.rho * (ct * c.e1 + st * c.e2);
  const Vec3 d1 = c.rho * (-st * c.e1 + ct * c.e2);
  const Vec3 d2 = -c.rho * (ct * c.e1 + st * c.e2);
  const double px = glm::dot(p, x), py = glm::dot(p, y), pz = glm::dot(p, z);
  const double q = px * px + py * py, s = std::sqrt(q);
  if (derivative == 0) {
    const double a = std::atan2(py, px);
    double u = a;
    const double rel = t - c.window;
    switch (branch) {
      case ArcBranch::Left: break;
      case ArcBranch::Right: u = a + kTwoPi; break;
      case ArcBranch::Inner: u = a < 0.0 ? a + kTwoPi : a; break;
      case ArcBranch::North:
        u = a < 0.0 ? a + kTwoPi : a;
        if (u < kWrapSlack && rel > M_PI) u += kTwoPi;
        if (u > kTwoPi - kWrapSlack && rel < M_PI) u -= kTwoPi;
        break;
      case ArcBranch::South:
        u = a < 0.0 ? a + kTwoPi : a;
        if (u < kWrapSlack && rel < M_PI) u += kTwoPi;
        if (u > kTwoPi - kWrapSlack && rel > M_PI) u -= kTwoPi;
        break;
    }
    out[0] = u;
    out[1] = std::atan2(pz, s);
    return;
  }
  const double dx = glm::dot(d1, x), dy = glm::dot(d1, y), dz = glm::dot(d1, z);
  const double cross = px * dy - py * dx, dot = px * dx + py * dy;
  const double ds = dot / s;
  if (derivative == 1) {
    out[0] = cross / q;
    out[1] = s * dz - pz * ds;  // d/dt atan2(pz, s), with pz^2 + s^2 = 1
    return;
  }
  const double ddx = glm::dot(d2, x), ddy = glm::dot(d2, y), ddz = glm::dot(d2, z);
  out[0] = (px * ddy - py * ddx) / q - cross * 2.0 * dot / (q * q);
  const double dds = (dx * dx + dy * dy + px * ddx + py * ddy) / s - dot * dot / (q * s);
  out[1] = s * ddz - pz * dds;
}

SphereLayout layout_sphere(const std::vector<SphereCap>& caps, SeamPreference preference) {
  SphereLayout layout;
  for (const SphereCap& cap : caps) {
    CircleLayout c;
    c.cap = cap;
    c.rho = std::sqrt(std::max(0.0, (1.0 - cap.exit) * (1.0 + cap.exit)));
    c.e1 = any_perpendicular(cap.direction);
    c.e2 = glm::cross(cap.direction, c.e1);
    layout.circles.push_back(c);
  }
  // Candidate poles.
  std::vector<Vec3> poles;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < kFibonacciPoles; ++i) {
    const double zc = 1.0 - (2.0 * i + 1.0) / kFibonacciPoles, r = std::sqrt(1.0 - zc * zc);
    poles.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), zc);
  }
  for (const SphereCap& cap : caps) {
    poles.push_back(cap.direction);
    poles.push_back(-cap.direction);
  }
  SphereFrame best{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
  const int sign = preference == SeamPreference::FewestCrossings ? -1 : 1;
  // A circle crossing the seam twice (a straddle) is valid in OpenCASCADE but does not survive a STEP round trip:
  // readers rebuild the face's wires from the file's loops and make the straddle a closed hole across the periodic
  // boundary ("intersecting wires", docs/brep.md section 2). With the fewest crossings, a frame without straddles
  // is taken whenever one has a workable margin.
  auto rank = [&](const Evaluation& e) {
    const bool good = e.margin >= kGoodLayoutMargin;
    const bool portable = preference == SeamPreference::FewestCrossings && e.straddles == 0 &&
                          e.margin >= kPortableLayoutMargin;
    return std::make_tuple(portable, good, good ? sign * e.crossing_circles : 0, e.margin);
  };
  Evaluation best_eval;
  if (!caps.empty()) {
    for (const Vec3& z : poles) {
      const Vec3 x0 = any_perpendicular(z), y0 = glm::cross(z, x0);
      for (int k = 0; k < kSeamLongitudes; ++k) {
        const double a = kTwoPi * k / kSeamLongitudes;
        SphereFrame f;
        f.z = z;
        f.x = std::cos(a) * x0 + std::sin(a) * y0;
        f.y = glm::cross(f.z, f.x);
        const Evaluation e = evaluate(layout.circles, f);
        if (!e.usable) continue;
        if (!best_eval.usable || rank(e) > rank(best_eval)) {
          best_eval = e;
          best = f;
        }
      }
    }
    if (!best_eval.usable || best_eval.margin < kMinimumLayoutMargin)
      fail_input("hub", "the exit circles leave no room on the sphere for a seam and poles (" +
                            std::to_string(caps.size()) + " beams): the hub is too crowded for one spherical face");
    layout.margin = best_eval.margin;
  } else {
    layout.margin = M_PI;
  }
  layout.z = best.z;
  layout.x = best.x;

  std::vector<std::pair<double, int>> straddles;
  for (int i = 0; i < static_cast<int>(layout.circles.size()); ++i) {
    CircleLayout& c = layout.circles[i];
    const double theta = std::acos(std::clamp(c.cap.exit, -1.0, 1.0));
    const double to_north = angle_between(best.z, c.cap.direction);
    const std::vector<double> ts = seam_crossings(c, best);
    auto latitude = [&](double t) { return std::asin(std::clamp(glm::dot(c.point(t), best.z), -1.0, 1.0)); };
    if (ts.empty()) {
      c.role = CircleRole::Inner;
      c.window = 0.0;
      c.own_vertices = {0.0};
      c.arcs = {{0.0, kTwoPi, ArcBranch::Inner}};
      continue;
    }
    if (ts.size() == 1) {
      const bool north = to_north < theta;
      c.role = north ? CircleRole::North : CircleRole::South;
      (north ? layout.north : layout.south) = i;
      c.window = wrap_into(ts[0], 0.0);
      c.own_vertices = {c.window};
      c.crossing_v = {latitude(c.window)};
      c.arcs = {{c.window, c.window + kTwoPi, north ? ArcBranch::North : ArcBranch::South}};
      continue;
    }
    c.role = CircleRole::Straddle;
    double lo = ts[0], hi = ts[1];
    if (latitude(lo) > latitude(hi)) std::swap(lo, hi);
    c.window = wrap_into(lo, 0.0);
    const double hi_w = wrap_into(hi, c.window);
    c.own_vertices = {c.window, hi_w};
    c.crossing_v = {latitude(c.window), latitude(hi_w)};
    const Vec3 y = best.y;
    auto side = [&](double t0, double t1) {
      const Vec3 mid = c.point(0.5 * (t0 + t1));
      return std::atan2(glm::dot(mid, y), glm::dot(mid, best.x)) > 0.0 ? ArcBranch::Left : ArcBranch::Right;
    };
    c.arcs = {{c.window, hi_w, side(c.window, hi_w)}, {hi_w, c.window + kTwoPi, side(hi_w, c.window + kTwoPi)}};
    straddles.emplace_back(c.crossing_v[0], i);
  }
  std::sort(straddles.begin(), straddles.end());
  for (const auto& s : straddles) layout.straddles.push_back(s.second);
  return layout;
}

}  // namespace steady
