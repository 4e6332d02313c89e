#include "lattice/direction_sets.hpp"

#include <cmath>

#include "lattice/circle_frames.hpp"

namespace steady {

namespace {

Mat3 frame_from(const Vec3& z, const Vec3& toward_x) {
  const Vec3 x = glm::normalize(toward_x - glm::dot(toward_x, z) * z);
  return Mat3(x, glm::cross(z, x), z);
}

double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// Every rotated canonical direction lands within `slack` of a distinct world direction.
bool carries_onto(const Mat3& rotation, const std::vector<Vec3>& canonical, const std::vector<Vec3>& world,
                  double slack) {
  std::vector<bool> used(world.size(), false);
  for (const Vec3& c : canonical) {
    const Vec3 w = rotation * c;
    std::size_t best = world.size();
    double nearest = slack;
    for (std::size_t k = 0; k < world.size(); ++k) {
      const double d = glm::length(world[k] - w);
      if (!used[k] && d <= nearest) best = k, nearest = d;
    }
    if (best == world.size()) return false;
    used[best] = true;
  }
  return true;
}

}  // namespace

DirectionFrame direction_frame(const std::vector<Vec3>& directions) {
  DirectionFrame f;
  if (directions.empty()) return f;
  const Vec3 z = directions[0];
  for (std::size_t s = 1; s < directions.size(); ++s)
    if (glm::length(glm::cross(directions[s], z)) > kDirectionFrameSine) {
      f.rotation = frame_from(z, directions[s]);
      f.second = static_cast<int>(s);
      return f;
    }
  f.rotation = frame_from(z, any_perpendicular(z));
  return f;
}

double pairwise_dot_sum(const std::vector<Vec3>& directions) {
  double sum = 0.0;
  for (std::size_t a = 0; a < directions.size(); ++a)
    for (std::size_t b = a + 1; b < directions.size(); ++b) sum += glm::dot(directions[a], directions[b]);
  return sum;
}

bool match_direction_set(const std::vector<Vec3>& canonical, int second, const std::vector<Vec3>& world,
                         double tolerance, Mat3& rotation) {
  if (canonical.size() != world.size() || world.empty()) return false;
  if (second < 0) {  // all on one axis: any rotation carrying +z to a world direction will do
    for (const Vec3& z : world) {
      rotation = frame_from(z, any_perpendicular(z));
      if (carries_onto(rotation, canonical, world, 4.0 * tolerance)) return true;
    }
    return false;
  }
  const double angle = angle_between(canonical[0], canonical[second]);
  const double sine = std::sin(angle);
  // An error e in the two directions that fix the frame turns it by up to about e / sine.
  const double slack = tolerance * (4.0 + 4.0 / sine);
  for (std::size_t i = 0; i < world.size(); ++i)
    for (std::size_t j = 0; j < world.size(); ++j) {
      if (i == j || std::abs(angle_between(world[i], world[j]) - angle) > 2.0 * tolerance) continue;
      rotation = frame_from(world[i], world[j]);
      if (carries_onto(rotation, canonical, world, slack)) return true;
    }
  return false;
}

}  // namespace steady
