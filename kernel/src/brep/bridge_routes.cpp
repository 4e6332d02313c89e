// The routes of bridges: capsule tests, and the rerouting of blocked bridges (brep/bridge_routes.hpp).
#include "brep/bridge_routes.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepLProp_SLProps.hxx>
#include <Precision.hxx>
#include <gp_Lin.hxx>

#include <algorithm>
#include <cmath>

#include "steady/core/constants.hpp"
#include "core/segment_distance.hpp"

namespace steady::bridges {

bool Clearance::meets_kept_element(const Bridge& br) const {
  const Vec3 from = f_.balls[br.hub].center;
  for (std::int64_t k = 0; k < f_.ball_count(); ++k) {
    if (!kept_[k] || k == br.hub) continue;
    if (point_segment_distance(f_.balls[k].center, from, br.end) < f_.balls[k].radius + br.radius + gap_) return true;
  }
  for (const FlatBeam& b : f_.beams) {
    if (!kept_[b.a] || !kept_[b.b] || b.a == br.hub || b.b == br.hub) continue;
    if (segment_distance(from, br.end, f_.balls[b.a].center, f_.balls[b.b].center) <
        std::max(b.ra, b.rb) + br.radius + gap_)
      return true;
  }
  return false;
}

bool Clearance::meets_bridge(const Bridge& br, const std::vector<Bridge>& made) const {
  const Vec3 from = f_.balls[br.hub].center;
  for (const Bridge& other : made)
    if (other.hub != br.hub &&
        segment_distance(from, br.end, f_.balls[other.hub].center, other.end) < br.radius + other.radius + gap_)
      return true;
  return false;
}

std::vector<Vec3> reroute_directions(const Vec3& nearest, const std::vector<Vec3>& lost) {
  std::vector<Vec3> out(lost.begin(), lost.begin() + std::min<std::size_t>(lost.size(), kLostBeamRoutes));
  // A fixed frame about `nearest`: its first axis across the coordinate axis least aligned with it.
  int least = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(nearest[k]) < std::abs(nearest[least])) least = k;
  Vec3 axis(0.0);
  axis[least] = 1.0;
  const Vec3 e1 = glm::normalize(glm::cross(nearest, axis)), e2 = glm::cross(nearest, e1);
  for (int ring = 1; ring <= kRings; ++ring) {
    const double tilt = ring * kRingStepDegrees * kPi / 180.0;
    for (int j = 0; j < kRingDirections; ++j) {
      const double turn = 2.0 * kPi * j / kRingDirections;
      out.push_back(std::cos(tilt) * nearest + std::sin(tilt) * (std::cos(turn) * e1 + std::sin(turn) * e2));
    }
  }
  return out;
}

BridgeRouter::BridgeRouter(const FlatLattice& f, const SolidBody& wall) : f_(f), reach_(2.0 * wall.size()) {
  rays_.Load(wall.solid(), Precision::Confusion());
}

std::optional<Bridge> BridgeRouter::route(std::int64_t hub, double radius, const Vec3& direction) {
  const Vec3 c = f_.balls[hub].center;
  rays_.Perform(gp_Lin(gp_Pnt(c.x, c.y, c.z), gp_Dir(direction.x, direction.y, direction.z)), 0.0, reach_);
  if (!rays_.IsDone() || rays_.NbPnt() == 0) return std::nullopt;
  rays_.SortResult();
  // The wall's normal at the first hit: how obliquely the route meets it.
  BRepLProp_SLProps props(BRepAdaptor_Surface(rays_.Face(1)), rays_.UParameter(1), rays_.VParameter(1), 1,
                          Precision::Confusion());
  if (!props.IsNormalDefined()) return std::nullopt;
  const gp_Dir& n = props.Normal();
  const double cos_incidence = std::abs(n.X() * direction.x + n.Y() * direction.y + n.Z() * direction.z);
  if (cos_incidence < std::cos(kMaxIncidenceDegrees * kPi / 180.0)) return std::nullopt;
  const gp_Pnt& p = rays_.Pnt(1);
  Bridge b;
  b.hub = hub;
  b.radius = radius;
  b.wall = Vec3(p.X(), p.Y(), p.Z());
  b.end = b.wall + direction * ((1.0 + kFarNodeClearance) * radius / cos_incidence);
  return b;
}

std::optional<Bridge> BridgeRouter::reroute(const Bridge& nearest, const std::vector<Vec3>& lost,
                                            const Clearance& clearance, const std::vector<Bridge>& made) {
  const Vec3 c = f_.balls[nearest.hub].center;
  std::optional<Bridge> best;
  double best_length = 0.0;
  for (const Vec3& direction : reroute_directions(glm::normalize(nearest.wall - c), lost)) {
    const std::optional<Bridge> b = route(nearest.hub, nearest.radius, direction);
    if (!b) continue;
    const double length = glm::length(b->wall - c);
    // Strictly shorter: among equal lengths the earlier candidate stays.
    if (best && length >= best_length) continue;
    if (!clearance.clear(*b, made)) continue;
    best = b;
    best_length = length;
  }
  if (best) best->rerouted = true;
  return best;
}

}  // namespace steady::bridges
