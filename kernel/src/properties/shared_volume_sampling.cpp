#include "properties/shared_volume_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "properties/quadratic_roots.hpp"
#include "steady/lattice/broad_phase.hpp"

namespace steady {

std::pair<Vec3, Vec3> hubs_bounds(const std::vector<Hub>& hubs) {
  Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const Hub& h : hubs) {
    lo = glm::min(lo, h.ball.center - Vec3(h.ball.radius));
    hi = glm::max(hi, h.ball.center + Vec3(h.ball.radius));
    for (const Stump& s : h.stumps) {
      lo = glm::min(lo, s.cut.center - Vec3(s.cut.radius));
      hi = glm::max(hi, s.cut.center + Vec3(s.cut.radius));
    }
  }
  return {lo, hi};
}

namespace {

// Where a stump's frustum lies along its axis: from where its cone touches the end ball to the cut. False when the
// stump holds nothing beyond its ball (one end ball inside the other, or the cut before that plane).
bool stump_span(const Stump& s, double& from, double& to) {
  if (!s.cone.has_lateral_surface()) return false;
  from = s.cone.ra * s.cone.sin_phi;
  to = s.cut_position;
  return to >= from;
}

}  // namespace

bool inside_hub(const Hub& h, const Vec3& p, HubReading reading) {
  const bool closed = reading == HubReading::ClosedAtCuts;
  bool inside = glm::dot(p - h.ball.center, p - h.ball.center) <= h.ball.radius * h.ball.radius;
  if (inside && !closed) return true;
  for (const Stump& s : h.stumps) {
    if (!s.cone.has_lateral_surface()) continue;
    double from = 0.0, to = 0.0;
    stump_span(s, from, to);
    const Vec3 d = p - s.cone.a;
    const double t = glm::dot(d, s.cone.axis);
    if (t < from || (t > to && !closed)) continue;
    const double r = s.cone.radius_at(t);
    if (!(glm::dot(d, d) - t * t <= r * r)) continue;
    if (t > to) return false;  // closed at the cut, and beyond its disk: the beam's, even inside the ball
    if (!closed) return true;
    inside = true;
  }
  return inside;
}

namespace {

Box disk_box(const Vec3& center, const Vec3& normal, double radius) {
  const Vec3 half = radius * glm::sqrt(glm::max(Vec3(0.0), Vec3(1.0) - normal * normal));
  return {center - half, center + half};
}

Box hull(const Box& a, const Box& b) { return {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)}; }

Box intersection(const Box& a, const Box& b) { return {glm::max(a.lo, b.lo), glm::min(a.hi, b.hi)}; }

double box_volume(const Box& b) {
  const Vec3 e = glm::max(Vec3(0.0), b.hi - b.lo);
  return e.x * e.y * e.z;
}

bool holds(const Box& b, const Vec3& p) {
  return p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y && p.z >= b.lo.z && p.z <= b.hi.z;
}

// The pieces inside_hub tests, each as its index (0 the ball, s + 1 stump s) and a box around it: the ball, and per
// stump the frustum from where its cone touches the end ball to the cut (the box of its two end disks holds it).
std::vector<std::pair<int, Box>> piece_boxes(const Hub& h) {
  const Vec3 reach(h.ball.radius);
  std::vector<std::pair<int, Box>> boxes{{0, {h.ball.center - reach, h.ball.center + reach}}};
  for (std::size_t k = 0; k < h.stumps.size(); ++k) {
    const BeamCone& cone = h.stumps[k].cone;
    double t0 = 0.0, t1 = 0.0;
    if (!stump_span(h.stumps[k], t0, t1)) continue;
    boxes.emplace_back(static_cast<int>(k) + 1,
                       hull(disk_box(cone.a + t0 * cone.axis, cone.axis, cone.radius_at(t0)),
                            disk_box(cone.a + t1 * cone.axis, cone.axis, cone.radius_at(t1))));
  }
  return boxes;
}

struct Piece {
  std::size_t hub;
  int index;  // 0 the ball, s + 1 stump s
  Box box;
};

// Per pair of hubs whose pieces' boxes meet, the box around all such meetings: every point two hubs hold lies in
// one of these.
std::vector<Box> meeting_regions(const std::vector<Piece>& pieces, std::size_t hubs) {
  std::vector<std::vector<Box>> of_hub(hubs);
  for (const Piece& p : pieces) of_hub[p.hub].push_back(p.box);
  std::vector<Box> regions;
  for (std::size_t a = 0; a < hubs; ++a)
    for (std::size_t b = a + 1; b < hubs; ++b) {
      bool met = false;
      Box region;
      for (const Box& pa : of_hub[a])
        for (const Box& pb : of_hub[b]) {
          if (!pa.overlaps(pb)) continue;
          const Box meeting = intersection(pa, pb);
          region = met ? hull(region, meeting) : meeting;
          met = true;
        }
      if (met && box_volume(region) > 0.0) regions.push_back(region);
    }
  return regions;
}

// Where the line origin + s z crosses the stump's cone and the planes of its span (where the cone touches its end
// ball, the cut).
void stump_crossings(const Stump& stump, const Vec3& origin, std::vector<double>& out) {
  if (!stump.cone.has_lateral_surface()) return;
  const Vec3 e(0.0, 0.0, 1.0);
  const BeamCone& cone = stump.cone;
  const Vec3 d0 = origin - cone.a;
  const double t0 = glm::dot(d0, cone.axis), tau = glm::dot(e, cone.axis);
  const double rho0 = (cone.ra - t0 * cone.sin_phi) / cone.cos_phi, rho1 = tau * cone.sin_phi / cone.cos_phi;
  // |d|^2 - t^2 - r(t)^2 with d = d0 + s e, t = t0 + s tau, r = rho0 - rho1 s.
  quadratic_roots(1.0 - tau * tau - rho1 * rho1, glm::dot(d0, e) - t0 * tau + rho0 * rho1,
                  glm::dot(d0, d0) - t0 * t0 - rho0 * rho0, out);
  double from = 0.0, to = 0.0;
  stump_span(stump, from, to);
  if (tau != 0.0)
    for (double plane : {from, to}) out.push_back((plane - t0) / tau);
}

// Where the line origin + s z may cross a piece's boundary: the roots of the sphere's or the cone's quadric and the
// frustum's two planes; for the ball of a hub closed at its cuts, also every stump's (what lies beyond a cut is
// taken out of the ball). A superset does no harm: the caller tests each stretch between them.
void piece_crossings(const Hub& h, int piece, HubReading reading, const Vec3& origin, std::vector<double>& out) {
  if (piece > 0) {
    stump_crossings(h.stumps[static_cast<std::size_t>(piece - 1)], origin, out);
    return;
  }
  const Vec3 d0 = origin - h.ball.center;
  quadratic_roots(1.0, d0.z, glm::dot(d0, d0) - h.ball.radius * h.ball.radius, out);
  if (reading == HubReading::ClosedAtCuts)
    for (const Stump& s : h.stumps) stump_crossings(s, origin, out);
}

}  // namespace

std::pair<double, double> sampled_shared_volume(const std::vector<Hub>& hubs, int lines, std::uint64_t seed,
                                                HubReading reading) {
  std::vector<Piece> pieces;
  for (std::size_t k = 0; k < hubs.size(); ++k)
    for (const auto& [index, box] : piece_boxes(hubs[k])) pieces.push_back({k, index, box});
  const std::vector<Box> regions = meeting_regions(pieces, hubs.size());
  if (regions.empty()) return {0.0, 0.0};
  double total = 0.0;
  for (const Box& r : regions) total += box_volume(r);
  // A few regions need fewer lines (a lone lens is measured to 1e-4 by 10,000); many share the budget.
  constexpr int kLinesPerRegion = 10000;
  lines = static_cast<int>(std::min<std::int64_t>(lines, std::int64_t{kLinesPerRegion} * regions.size()));
  constexpr int kReplicates = 8;
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double estimate = 0.0, variance = 0.0;
  std::vector<double> cuts;
  for (const Box& region : regions) {
    std::vector<const Piece*> near;
    std::vector<std::size_t> near_hubs;
    for (const Piece& p : pieces)
      if (p.box.overlaps(region)) {
        near.push_back(&p);
        if (std::find(near_hubs.begin(), near_hubs.end(), p.hub) == near_hubs.end()) near_hubs.push_back(p.hub);
      }
    std::vector<const Box*> neighbours;  // the regions that may share a point with this one
    for (const Box& other : regions)
      if (other.overlaps(region)) neighbours.push_back(&other);
    // The integrand along a line of this region: (hubs holding p - 1) / (regions holding p), exactly, from the
    // stretches between the line's crossings of the pieces' boundaries and of the regions' faces.
    auto line_integral = [&](double x, double y) {
      const Vec3 origin(x, y, 0.0);
      cuts.assign({region.lo.z, region.hi.z});
      for (const Box* other : neighbours)
        if (x >= other->lo.x && x <= other->hi.x && y >= other->lo.y && y <= other->hi.y)
          cuts.insert(cuts.end(), {other->lo.z, other->hi.z});
      for (const Piece* p : near) piece_crossings(hubs[p->hub], p->index, reading, origin, cuts);
      std::sort(cuts.begin(), cuts.end());
      double sum = 0.0;
      for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
        const double a = std::max(cuts[i], region.lo.z), b = std::min(cuts[i + 1], region.hi.z);
        if (!(b > a)) continue;
        const Vec3 mid(x, y, 0.5 * (a + b));
        int holding = 0;
        for (std::size_t k : near_hubs) holding += inside_hub(hubs[k], mid, reading) ? 1 : 0;
        if (holding < 2) continue;
        int covering = 0;
        for (const Box* other : neighbours) covering += holds(*other, mid) ? 1 : 0;
        sum += (holding - 1) * (b - a) / std::max(1, covering);
      }
      return sum;
    };
    // Replicates of a jittered grid over the region's (x, y) rectangle: each an unbiased estimate, their spread the
    // standard error.
    const int per_replicate = std::max(16, static_cast<int>(lines * box_volume(region) / total / kReplicates));
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(per_replicate))));
    const double dx = (region.hi.x - region.lo.x) / side, dy = (region.hi.y - region.lo.y) / side;
    double sum = 0.0, squares = 0.0;
    for (int r = 0; r < kReplicates; ++r) {
      double replicate = 0.0;
      for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j)
          replicate += line_integral(region.lo.x + (i + unit(random)) * dx, region.lo.y + (j + unit(random)) * dy);
      replicate *= dx * dy;
      sum += replicate;
      squares += replicate * replicate;
    }
    const double mean = sum / kReplicates;
    estimate += mean;
    variance += std::max(0.0, squares / kReplicates - mean * mean) / (kReplicates - 1);
  }
  return {estimate, std::sqrt(variance)};
}

}  // namespace steady
