#include "lattice/hub_catalog.hpp"

#include <tbb/parallel_for.h>

#include <cmath>
#include <unordered_map>

#include "lattice/circle_frames.hpp"
#include "steady/core/progress.hpp"

namespace steady {

namespace {

// A second stump this far from parallel to the first (sine of the angle) fixes the canonical rotation well.
constexpr double kFrameSine = 1e-3;
// Canonical values are hashed on this grid; matches are then confirmed to kHubMatchTolerance.
constexpr double kHashGrid = 1e-7;

std::uint64_t hash_caps(const std::vector<SphereCap>& caps, int kind, const std::vector<double>& extras) {
  std::uint64_t h = 1469598103934665603ull ^ (caps.size() * 4 + static_cast<std::uint64_t>(kind));
  auto mix = [&](double v) {
    const std::int64_t q = std::llround(v / kHashGrid);
    h ^= static_cast<std::uint64_t>(q) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
  };
  for (const SphereCap& c : caps) {
    mix(c.direction.x);
    mix(c.direction.y);
    mix(c.direction.z);
    mix(c.exit);
  }
  for (double x : extras) mix(x);
  return h;
}

bool same_caps(const std::vector<SphereCap>& a, const std::vector<SphereCap>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (glm::length(a[i].direction - b[i].direction) > kHubMatchTolerance) return false;
    if (std::abs(a[i].exit - b[i].exit) > kHubMatchTolerance) return false;
  }
  return true;
}

bool same_extras(const HubGeometry& a, const HubGeometry& b) {
  if (a.kind != b.kind || a.extras.size() != b.extras.size()) return false;
  for (std::size_t i = 0; i < a.extras.size(); ++i)
    if (std::abs(a.extras[i] - b.extras[i]) > kHubMatchTolerance) return false;
  return true;
}

}  // namespace

HubPlacement canonical_frame(const HubGeometry& hub) {
  HubPlacement p;
  if (hub.exits.empty()) return p;
  const Vec3 z = hub.exits[0].normal;
  Vec3 x(0.0);
  for (std::size_t s = 1; s < hub.exits.size(); ++s) {
    const Vec3 d = hub.exits[s].normal - glm::dot(hub.exits[s].normal, z) * z;
    if (glm::length(d) > kFrameSine) {
      x = glm::normalize(d);
      break;
    }
  }
  if (x == Vec3(0.0)) x = any_perpendicular(z);  // all stumps on one axis: the hub is symmetric about it
  p.rotation = Mat3(x, glm::cross(z, x), z);     // columns: the world images of canonical x, y, z
  return p;
}

std::vector<SphereCap> canonical_caps(const HubGeometry& hub, const Mat3& rotation) {
  const Mat3 to_canonical = glm::transpose(rotation);
  std::vector<SphereCap> caps;
  for (const Circle& c : hub.exits) {
    const double x = glm::dot(c.center - hub.ball.center, c.normal) / hub.ball.radius;
    caps.push_back({glm::normalize(to_canonical * c.normal), x});
  }
  return caps;
}

HubCatalog catalog_hubs(const std::vector<HubGeometry>& hubs) {
  const std::int64_t n = static_cast<std::int64_t>(hubs.size());
  HubCatalog cat;
  cat.placements.resize(n);
  std::vector<std::vector<SphereCap>> caps(n);
  std::vector<std::uint64_t> keys(n);
  Progress* const caller = current_progress();  // a million hubs take seconds: cancellable (Ctrl-C)
  tbb::parallel_for(std::int64_t(0), n, [&](std::int64_t h) {
    const ProgressScope scope(caller);
    if ((h & 1023) == 0) poll_progress();
    cat.placements[h] = canonical_frame(hubs[h]);
    caps[h] = canonical_caps(hubs[h], cat.placements[h].rotation);
    keys[h] = hash_caps(caps[h], hubs[h].kind, hubs[h].extras);
  });
  std::unordered_map<std::uint64_t, std::vector<int>> by_key;
  for (std::int64_t h = 0; h < n; ++h) {
    auto& candidates = by_key[keys[h]];
    int shape = -1;
    for (int s : candidates)
      if (same_caps(cat.shapes[s], caps[h]) && same_extras(hubs[cat.representatives[s]], hubs[h])) {
        shape = s;
        break;
      }
    if (shape < 0) {
      shape = static_cast<int>(cat.shapes.size());
      cat.shapes.push_back(std::move(caps[h]));
      cat.representatives.push_back(h);
      candidates.push_back(shape);
    }
    cat.placements[h].shape = shape;
  }
  return cat;
}

}  // namespace steady
